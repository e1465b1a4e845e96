#include "gui/x11_shm_sink.h"
#include "test_window.h"

#include <GLFW/glfw3.h>
#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3native.h>
// Xlib last: its macros (None, Bool, Status) would rename names in the headers above.
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

using namespace facesketch;

namespace {

// A bare GLFW window (no Vulkan): the sink draws into its X11 drawable.
struct BareWindow {
    BareWindow(int width, int height)
    {
        REQUIRE(glfwInit());
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
        window = glfwCreateWindow(width, height, "facesketch shm test", nullptr, nullptr);
        REQUIRE(window);
        glfwPollEvents();
    }
    ~BareWindow()
    {
        glfwDestroyWindow(window);
        glfwTerminate();
    }
    GLFWwindow* window = nullptr;
};

std::vector<std::uint8_t> pattern(VkExtent2D e, VkFormat format)
{
    std::vector<std::uint8_t> bytes(std::size_t(e.width) * e.height * 4);
    for (std::uint32_t y = 0; y < e.height; ++y)
        for (std::uint32_t x = 0; x < e.width; ++x) {
            std::uint8_t* p = &bytes[4 * (std::size_t(y) * e.width + x)];
            const std::uint8_t r = std::uint8_t(x * 5), g = std::uint8_t(y * 3), b = std::uint8_t(x ^ y);
            p[0] = format == VK_FORMAT_B8G8R8A8_UNORM ? b : r;
            p[1] = g;
            p[2] = format == VK_FORMAT_B8G8R8A8_UNORM ? r : b;
            p[3] = 255;
        }
    return bytes;
}

// What the X server holds in the window now, as (r, g, b) per pixel, read back by XGetImage:
// the server's own answer, not the sink's memory.
std::vector<std::array<std::uint8_t, 3>> windowPixels(GLFWwindow* window, VkExtent2D e)
{
    Display* display = glfwGetX11Display();
    XImage* image = XGetImage(display, glfwGetX11Window(window), 0, 0, e.width, e.height, AllPlanes, ZPixmap);
    REQUIRE(image);
    std::vector<std::array<std::uint8_t, 3>> rgb;
    for (std::uint32_t y = 0; y < e.height; ++y)
        for (std::uint32_t x = 0; x < e.width; ++x) {
            const unsigned long p = XGetPixel(image, int(x), int(y));
            auto channel = [&](unsigned long mask) {
                int shift = 0;
                while (!((mask >> shift) & 1))
                    ++shift;
                return std::uint8_t((p & mask) >> shift);
            };
            rgb.push_back({ channel(image->red_mask), channel(image->green_mask), channel(image->blue_mask) });
        }
    XDestroyImage(image);
    return rgb;
}

} // namespace

TEST_CASE("x11 shm sink: a frame shown by MIT-SHM is what the X server then holds in the window, pixel for pixel, also after a new size")
{
    if (!test::haveDisplay())
        return;
    BareWindow w(96, 64);
    std::string why;
    std::unique_ptr<gpu::FrameSink> sink = gui::createX11ShmSink(w.window, { 96, 64 }, why);
    INFO("why not: " << why);
    // Xvfb (and any local X server with a 24-bit TrueColor visual) attaches the segment.
    REQUIRE(sink);
    REQUIRE((sink->format() == VK_FORMAT_B8G8R8A8_UNORM || sink->format() == VK_FORMAT_R8G8B8A8_UNORM));
    for (VkExtent2D e : { VkExtent2D { 96, 64 }, VkExtent2D { 33, 21 } }) {
        const std::vector<std::uint8_t> bytes = pattern(e, sink->format());
        sink->show(bytes.data(), e); // returns once the server has copied it
        const auto rgb = windowPixels(w.window, e);
        int wrong = 0;
        for (std::uint32_t y = 0; y < e.height; ++y)
            for (std::uint32_t x = 0; x < e.width; ++x) {
                const std::array<std::uint8_t, 3> want { std::uint8_t(x * 5), std::uint8_t(y * 3), std::uint8_t(x ^ y) };
                wrong += rgb[std::size_t(y) * e.width + x] != want;
            }
        INFO(e.width << "x" << e.height);
        REQUIRE(wrong == 0);
    }
}

TEST_CASE("x11 shm sink: a window that is not an X11 window, or no GLFW at all, is refused with a reason")
{
    // Without glfwInit, GLFW has no X11 display: the sink says so instead of crashing.
    std::string why;
    REQUIRE_FALSE(gui::createX11ShmSink(nullptr, { 8, 8 }, why));
    REQUIRE(why.find("X11") != std::string::npos);
}

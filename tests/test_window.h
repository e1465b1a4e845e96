#pragma once
// A GLFW window with its own Vulkan instance, surface and presenting device, for the tests of
// the frame loop (tests/gpu/swapchain.cpp, tests/render/pass.cpp). Needs an X display: ctest is
// run under `xvfb-run -a` by tools/test.sh; without DISPLAY the tests say why and skip.

#include "gpu/device.h"

#include <GLFW/glfw3.h>
#include <catch2/catch.hpp>

#include <cfenv>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace facesketch::test {

/// True when an X display is there to open windows on; otherwise WARNs the reason.
inline bool haveDisplay()
{
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        WARN("skipped: DISPLAY is unset (run under xvfb-run -a, as tools/test.sh does)");
        return false;
    }
    return true;
}

class TestWindow {
public:
    TestWindow(int width, int height)
    {
        // As test::device() does: Mesa computes with floating-point exceptions masked, so the
        // traps the debug test main arms are lifted for a process that uses the GPU.
        fedisableexcept(FE_ALL_EXCEPT);
        if (!glfwInit())
            throw std::runtime_error("glfwInit failed (DISPLAY=" + std::string(std::getenv("DISPLAY")) + ")");
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        window = glfwCreateWindow(width, height, "facesketch test", nullptr, nullptr);
        if (!window) {
            glfwTerminate();
            throw std::runtime_error("glfwCreateWindow failed");
        }
        std::uint32_t count = 0;
        const char** extensions = glfwGetRequiredInstanceExtensions(&count);
        instance = gpu::createInstance(
            { .validation = true, .requireValidation = true, .extensions = std::vector<const char*>(extensions, extensions + count) });
        if (glfwCreateWindowSurface(instance.instance, window, nullptr, &surface) != VK_SUCCESS)
            throw std::runtime_error("glfwCreateWindowSurface failed");
        device = gpu::createDevice(instance, gpu::choosePhysicalDevice(instance, surface), { .swapchain = true });
    }
    ~TestWindow()
    {
        gpu::destroyDevice(device);
        vkDestroySurfaceKHR(instance.instance, surface, nullptr);
        gpu::destroyInstance(instance);
        glfwDestroyWindow(window);
        glfwTerminate();
    }
    TestWindow(const TestWindow&) = delete;
    TestWindow& operator=(const TestWindow&) = delete;

    /// The framebuffer size in pixels, after letting the window system catch up.
    VkExtent2D framebufferSize()
    {
        glfwPollEvents();
        int w = 0, h = 0;
        glfwGetFramebufferSize(window, &w, &h);
        return { std::uint32_t(w), std::uint32_t(h) };
    }

    GLFWwindow* window = nullptr;
    gpu::Instance instance;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    gpu::Device device;
};

} // namespace facesketch::test

#include "gpu/swapchain.h"
#include "core/error.h"
#include "gpu/buffers.h"
#include "gpu/compute.h"
#include "test_common.h"
#include "test_window.h"

#include <chrono>
#include <thread>

using namespace facesketch;

namespace {

// Clears the frame's image to `rgba` and, when `readback` is given, copies it there.
void clearFrame(const gpu::Frame& frame, VkClearColorValue rgba, const gpu::Buffer* readback)
{
    gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    const VkImageSubresourceRange range { VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1 };
    vkCmdClearColorImage(frame.cmd, frame.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &rgba, 1, &range);
    VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    if (readback) {
        gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        VkBufferImageCopy region {};
        region.imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 };
        region.imageExtent = { frame.extent.width, frame.extent.height, 1 };
        vkCmdCopyImageToBuffer(frame.cmd, frame.image, layout, readback->buffer, 1, &region);
        gpu::hostReadBarrier(frame.cmd);
    }
    gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
        0);
}

// Polls until the window system reports the new framebuffer size (Xvfb answers within a few
// events), or gives up after a second.
VkExtent2D waitForSize(test::TestWindow& w, VkExtent2D want)
{
    VkExtent2D size = w.framebufferSize();
    for (int i = 0; i < 100 && (size.width != want.width || size.height != want.height); ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        size = w.framebufferSize();
    }
    return size;
}

} // namespace

TEST_CASE("swapchain: frames are cleared and presented, the image reads back, resizes recreate and a zero size skips")
{
    if (!test::haveDisplay())
        return;
    test::TestWindow w(128, 96);
    REQUIRE(w.device.swapchain);
    const std::uint64_t before = gpu::validationMessageCount();
    {
        gpu::FrameLoop loop(w.device, w.surface, w.framebufferSize(), { .srgb = false, .extraUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT });
        const gpu::Swapchain& sc = loop.swapchain();
        REQUIRE(sc.swapchain != VK_NULL_HANDLE);
        REQUIRE(sc.extent.width == 128);
        REQUIRE(sc.extent.height == 96);
        REQUIRE((sc.format == VK_FORMAT_B8G8R8A8_UNORM || sc.format == VK_FORMAT_R8G8B8A8_UNORM));
        REQUIRE(sc.images.size() >= 2);

        gpu::Buffer readback = gpu::createBuffer(w.device, 128 * 96 * 4, 0, gpu::MemoryUse::Readback);
        int released = 0;
        for (int i = 0; i < 12; ++i) {
            gpu::Frame frame;
            REQUIRE(loop.beginFrame(w.framebufferSize(), frame));
            REQUIRE(frame.slot == std::uint32_t(i % gpu::framesInFlight));
            REQUIRE(frame.number == std::uint64_t(i + 1));
            clearFrame(frame, { { 0.0f, 0.5f, 1.0f, 1.0f } }, i == 5 ? &readback : nullptr);
            if (i == 5)
                loop.defer([&] { ++released; });
            loop.endFrame(frame);
            // A release runs only after the frames in flight at its deferral have finished.
            if (i == 5)
                REQUIRE(released == 0);
            if (i == 5 + int(gpu::framesInFlight))
                REQUIRE(released == 1);
        }
        REQUIRE(loop.framesBegun() == 12);
        loop.waitFrames();
        // Frame 6's image after its fence: blue 255, green 128, red 0 in either byte order.
        const auto* pixel = static_cast<const std::uint8_t*>(readback.mapped) + 4 * (40 * 128 + 70);
        const bool bgra = sc.format == VK_FORMAT_B8G8R8A8_UNORM;
        REQUIRE(int(pixel[bgra ? 0 : 2]) == 255);
        REQUIRE(int(pixel[1]) == 128);
        REQUIRE(int(pixel[bgra ? 2 : 0]) == 0);
        gpu::destroyBuffer(w.device, readback);

        glfwSetWindowSize(w.window, 200, 100);
        const VkExtent2D resized = waitForSize(w, { 200, 100 });
        REQUIRE(resized.width == 200);
        REQUIRE(resized.height == 100);
        for (int i = 0; i < 4; ++i) {
            gpu::Frame frame;
            REQUIRE(loop.beginFrame(resized, frame));
            REQUIRE(frame.extent.width == 200);
            REQUIRE(frame.extent.height == 100);
            clearFrame(frame, { { 1.0f, 0.0f, 0.0f, 1.0f } }, nullptr);
            loop.endFrame(frame);
        }
        REQUIRE(loop.swapchain().extent.width == 200);

        // Minimised: no frame, nothing begun, and the loop carries on afterwards.
        gpu::Frame frame;
        REQUIRE_FALSE(loop.beginFrame({ 0, 0 }, frame));
        REQUIRE(loop.framesBegun() == 16);
        REQUIRE(loop.beginFrame(resized, frame));
        clearFrame(frame, { { 0.0f, 0.0f, 0.0f, 1.0f } }, nullptr);
        loop.endFrame(frame);
        REQUIRE_THROWS_AS(loop.endFrame(frame), Error);
    }
    REQUIRE(gpu::validationMessageCount() == before);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("swapchain: a device without VK_KHR_swapchain cannot make one")
{
    if (!test::haveDisplay())
        return;
    test::TestWindow w(64, 64);
    gpu::Device headless = gpu::createDevice(w.instance, gpu::choosePhysicalDevice(w.instance, w.surface));
    REQUIRE_THROWS_WITH(gpu::createSwapchain(headless, w.surface, { 64, 64 }), Catch::Contains("VK_KHR_swapchain"));
    gpu::destroyDevice(headless);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

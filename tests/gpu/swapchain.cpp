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

namespace {

// A frame sink that keeps what it was shown: the CPU side of the sink-mode test.
struct KeepingSink final : gpu::FrameSink {
    VkFormat format() const override { return VK_FORMAT_B8G8R8A8_UNORM; }
    void show(const std::uint8_t* pixels, VkExtent2D extent) override
    {
        shown.emplace_back(pixels, pixels + std::size_t(extent.width) * extent.height * 4);
        extents.push_back(extent);
    }
    std::vector<std::vector<std::uint8_t>> shown;
    std::vector<VkExtent2D> extents;
};

// Fills the frame's image from `pattern` (its bytes, rows top first) and leaves it to be shown.
void copyFrame(const gpu::Frame& frame, const gpu::Buffer& pattern)
{
    gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region {};
    region.imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 };
    region.imageExtent = { frame.extent.width, frame.extent.height, 1 };
    vkCmdCopyBufferToImage(frame.cmd, pattern.buffer, frame.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
        VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
        0);
}

std::vector<std::uint8_t> patternBytes(VkExtent2D e, int frame)
{
    std::vector<std::uint8_t> bytes(std::size_t(e.width) * e.height * 4);
    for (std::uint32_t y = 0; y < e.height; ++y)
        for (std::uint32_t x = 0; x < e.width; ++x) {
            std::uint8_t* p = &bytes[4 * (std::size_t(y) * e.width + x)];
            p[0] = std::uint8_t(x * 7 + frame);
            p[1] = std::uint8_t(y * 5);
            p[2] = std::uint8_t(x + y * 3 + 11 * frame);
            p[3] = 255;
        }
    return bytes;
}

} // namespace

TEST_CASE("swapchain: a loop without a swapchain hands every finished frame to its sink, byte for byte, and remakes its images on a resize")
{
    if (!test::haveDisplay())
        return;
    test::TestWindow w(64, 64);
    const std::uint64_t before = gpu::validationMessageCount();
    {
        auto owned = std::make_unique<KeepingSink>();
        KeepingSink& sink = *owned;
        gpu::FrameLoop loop(w.device, std::move(owned), { 40, 30 });
        REQUIRE(loop.presentsToSink());
        REQUIRE(loop.swapchain().swapchain == VK_NULL_HANDLE);
        REQUIRE(loop.swapchain().format == VK_FORMAT_B8G8R8A8_UNORM);
        REQUIRE(loop.swapchain().images.size() == gpu::framesInFlight);
        const std::uint64_t generation = loop.imagesGeneration();

        int frameIndex = 0;
        auto drawFrames = [&](VkExtent2D size, int count) {
            gpu::Buffer pattern = gpu::createBuffer(w.device, VkDeviceSize(size.width) * size.height * 4, 0, gpu::MemoryUse::Upload);
            for (int i = 0; i < count; ++i, ++frameIndex) {
                gpu::Frame frame;
                REQUIRE(loop.beginFrame(size, frame));
                REQUIRE(frame.extent.width == size.width);
                REQUIRE(frame.extent.height == size.height);
                REQUIRE(frame.image == loop.swapchain().images[frame.imageIndex]);
                // Each frame's own pattern: written after the last frame's copy read the buffer
                // (endFrame has waited for it to be shown).
                const std::vector<std::uint8_t> want = patternBytes(size, frameIndex);
                gpu::uploadBuffer(w.device, pattern, want.data(), want.size());
                copyFrame(frame, pattern);
                loop.endFrame(frame);
                // Shown by the time endFrame returns, exactly the bytes drawn.
                REQUIRE(sink.shown.size() == std::size_t(frameIndex + 1));
                REQUIRE(sink.extents.back().width == size.width);
                REQUIRE(sink.shown.back() == want);
            }
            gpu::destroyBuffer(w.device, pattern);
        };
        drawFrames({ 40, 30 }, 3);
        REQUIRE(loop.imagesGeneration() == generation);
        drawFrames({ 17, 50 }, 3); // an odd width: rows must not be padded
        REQUIRE(loop.imagesGeneration() == generation + 1);
        REQUIRE(loop.swapchain().extent.width == 17);

        // Minimised: no frame, nothing shown; the loop carries on afterwards.
        gpu::Frame frame;
        REQUIRE_FALSE(loop.beginFrame({ 0, 0 }, frame));
        REQUIRE(sink.shown.size() == 6);
        drawFrames({ 17, 50 }, 1);
    }
    REQUIRE(gpu::validationMessageCount() == before);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("swapchain: a frame sink must take an 8-bit BGRA or RGBA format")
{
    if (!test::haveDisplay())
        return;
    struct FloatSink final : gpu::FrameSink {
        VkFormat format() const override { return VK_FORMAT_R32G32B32A32_SFLOAT; }
        void show(const std::uint8_t*, VkExtent2D) override { }
    };
    test::TestWindow w(32, 32);
    REQUIRE_THROWS_WITH(gpu::FrameLoop(w.device, std::make_unique<FloatSink>(), VkExtent2D { 8, 8 }), Catch::Contains("B8G8R8A8_UNORM"));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

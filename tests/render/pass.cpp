#include "render/pass.h"
#include "core/error.h"
#include "geometry/primitives.h"
#include "gpu/compute.h"
#include "gpu/swapchain.h"
#include "render/renderer.h"
#include "test_common.h"
#include "test_window.h"

#include <cstring>

using namespace facesketch;

TEST_CASE("pass: a window frame drawn by the scene renderer equals the offscreen image, frame after frame")
{
    if (!test::haveDisplay())
        return;
    const int w = 120, h = 90;
    test::TestWindow window(w, h);
    gpu::Device& d = window.device;
    const Mesh sphere = makeIcosphere(1.0, 3);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.2, { 30, 15 }, w, h);
    std::vector<glm::vec3> cross { { -1.2f, 0, 1.1f }, { 1.2f, 0, 1.1f }, { 0, -1.2f, 1.1f }, { 0, 1.2f, 1.1f } };

    // The reference: the offscreen renderer on the same device.
    Image expected;
    {
        Renderer offscreen(d, w, h, 4);
        offscreen.addMesh(sphere);
        offscreen.addLines(cross, { { 0.9f, 0.1f, 0.1f, 1.0f } });
        expected = offscreen.render(camera, { 1, 1, 1, 1 });
    }

    const std::uint64_t before = gpu::validationMessageCount();
    {
        gpu::FrameLoop loop(d, window.surface, window.framebufferSize());
        const VkFormat format = loop.swapchain().format;
        SceneRenderer scene(d, { .color = format, .depth = VK_FORMAT_D32_SFLOAT, .samples = 4 }, gpu::framesInFlight);
        const DrawId face = scene.addMesh(sphere);
        scene.addLines(cross, { { 0.9f, 0.1f, 0.1f, 1.0f } });
        PassTargets targets = createPassTargets(d, scene.target(), loop.swapchain().extent);
        gpu::Buffer readback = gpu::createBuffer(d, VkDeviceSize(w) * h * 4, 0, gpu::MemoryUse::Readback);

        // Frames 1-4 draw a squashed face (each slot's copy gets it), frame 5 the original
        // again: the slot it lands in must have been refreshed, or the picture differs.
        Mesh squashed = sphere;
        squashed.V.col(1) *= 0.5;
        for (int i = 0; i < 5; ++i) {
            scene.updateMesh(face, i < 4 ? squashed.V : sphere.V);
            gpu::Frame frame;
            REQUIRE(loop.beginFrame(window.framebufferSize(), frame));
            REQUIRE(frame.extent.width == std::uint32_t(w));
            beginPass(d, frame.cmd, targets, frame.image, frame.view, { 1, 1, 1, 1 });
            scene.record(frame.cmd, frame.slot, camera, frame.extent);
            const bool last = i == 4;
            endPass(d, frame.cmd, frame.image, last ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
            if (last) {
                VkBufferImageCopy region {};
                region.imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 };
                region.imageExtent = { frame.extent.width, frame.extent.height, 1 };
                vkCmdCopyImageToBuffer(frame.cmd, frame.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &region);
                gpu::hostReadBarrier(frame.cmd);
                gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                    VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
            }
            loop.endFrame(frame);
        }
        loop.waitFrames();

        Image image;
        image.width = w;
        image.height = h;
        image.pixels.resize(static_cast<size_t>(w) * h * 4);
        std::memcpy(image.pixels.data(), readback.mapped, image.pixels.size());
        if (format == VK_FORMAT_B8G8R8A8_UNORM)
            for (size_t p = 0; p < image.pixels.size(); p += 4)
                std::swap(image.pixels[p], image.pixels[p + 2]);
        REQUIRE((format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_R8G8B8A8_UNORM));
        long differing = 0;
        for (size_t p = 0; p < image.pixels.size(); ++p)
            differing += image.pixels[p] != expected.pixels[p];
        INFO(differing << " bytes differ");
        REQUIRE(image.pixels == expected.pixels);

        gpu::destroyBuffer(d, readback);
        destroyPassTargets(d, targets);
    }
    REQUIRE(gpu::validationMessageCount() == before);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("pass: targets of a bad size or for a render pass are errors")
{
    gpu::Device& d = test::device();
    REQUIRE_THROWS_AS(createPassTargets(d, {}, { 0, 10 }), Error);
    REQUIRE_THROWS_AS(
        createPassTargets(d, { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 3 }, { 8, 8 }), Error);
    PassTargets t = createPassTargets(d, { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 4 }, { 8, 6 });
    REQUIRE(t.color.image != VK_NULL_HANDLE);
    REQUIRE(t.depth.width == 8);
    REQUIRE(t.depth.height == 6);
    destroyPassTargets(d, t);
    PassTargets single = createPassTargets(d, { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, { 8, 6 });
    REQUIRE(single.color.image == VK_NULL_HANDLE);
    destroyPassTargets(d, single);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

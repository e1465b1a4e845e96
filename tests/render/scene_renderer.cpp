#include "render/scene_renderer.h"
#include "core/error.h"
#include "geometry/primitives.h"
#include "gpu/buffers.h"
#include "gpu/compute.h"
#include "gpu/swapchain.h"
#include "render/pass.h"
#include "render/renderer.h"
#include "test_common.h"

#include <cmath>
#include <cstring>

using namespace facesketch;

namespace {

// Draws `scene` (made for dynamic rendering, R8G8B8A8_UNORM) with render/pass into an image
// of its own and reads it back after the submission's fence.
// `target`/`format`: another of the scene's targets (addTarget) and its format.
Image drawDynamic(SceneRenderer& scene, std::uint32_t slot, const Camera& camera, int width, int height, glm::vec4 background,
    float pixelScale = 1.0f, std::uint32_t target = 0, const RenderTargetFormat* format = nullptr)
{
    gpu::Device& d = test::device();
    const VkExtent2D extent { std::uint32_t(width), std::uint32_t(height) };
    PassTargets targets = createPassTargets(d, format ? *format : scene.target(), extent);
    gpu::Image output = gpu::createImage(d, extent.width, extent.height, scene.target().color,
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    gpu::Buffer readback = gpu::createBuffer(d, VkDeviceSize(width) * height * 4, 0, gpu::MemoryUse::Readback);
    gpu::submitAndWait(d, [&](VkCommandBuffer cmd) {
        beginPass(d, cmd, targets, output.image, output.view, background);
        scene.record(cmd, slot, camera, extent, pixelScale, target);
        endPass(d, cmd, output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region {};
        region.imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 };
        region.imageExtent = { extent.width, extent.height, 1 };
        vkCmdCopyImageToBuffer(cmd, output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &region);
        gpu::hostReadBarrier(cmd);
    });
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.resize(static_cast<size_t>(width) * height * 4);
    std::memcpy(image.pixels.data(), readback.mapped, image.pixels.size());
    gpu::destroyBuffer(d, readback);
    gpu::destroyImage(d, output);
    destroyPassTargets(d, targets);
    return image;
}

// The first differing pixel, for a readable failure.
std::string firstDifference(const Image& a, const Image& b)
{
    if (a.width != b.width || a.height != b.height)
        return "sizes differ";
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            if (std::memcmp(a.at(x, y), b.at(x, y), 4) != 0)
                return cat("pixel (", x, ", ", y, "): ", int(a.at(x, y)[0]), ",", int(a.at(x, y)[1]), ",", int(a.at(x, y)[2]), ",",
                    int(a.at(x, y)[3]), " vs ", int(b.at(x, y)[0]), ",", int(b.at(x, y)[1]), ",", int(b.at(x, y)[2]), ",",
                    int(b.at(x, y)[3]));
    return "identical";
}

// A sphere with a ring of lines and a few points: every kind of world-space item.
void addTestScene(SceneRenderer& scene, const Mesh& sphere)
{
    scene.addMesh(sphere, MeshStyle { { 0.7f, 0.6f, 0.5f, 1.0f }, true });
    std::vector<glm::vec3> ring;
    for (int i = 0; i < 32; ++i)
        for (int k : { i, i + 1 }) {
            const double a = 2 * M_PI * k / 32;
            ring.push_back({ float(1.05 * std::cos(a)), float(1.05 * std::sin(a)), 0.2f });
        }
    scene.addLines(ring, { { 0.1f, 0.2f, 0.9f, 1.0f } });
    scene.addPoints({ { 0, 0, 1.05f }, { 0.5f, 0.5f, 0.9f } }, { { 1, 0, 0, 1 }, { 0, 1, 0, 1 } }, 5.0f);
}

} // namespace

TEST_CASE("scene renderer: dynamic rendering through render/pass gives the offscreen render pass image byte for byte")
{
    const int w = 96, h = 80;
    const Mesh sphere = makeIcosphere(1.0, 3);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.1, { 20, 10 }, w, h);
    for (int samples : { 1, 4 }) {
        INFO("samples " << samples);
        Renderer offscreen(test::device(), w, h, samples);
        addTestScene(offscreen.scene(), sphere);
        const Image expected = offscreen.render(camera, { 0.9f, 0.95f, 1.0f, 1.0f });

        SceneRenderer scene(test::device(), { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = samples }, 1);
        addTestScene(scene, sphere);
        const Image image = drawDynamic(scene, 0, camera, w, h, { 0.9f, 0.95f, 1.0f, 1.0f });
        INFO(firstDifference(image, expected));
        REQUIRE(image.pixels == expected.pixels);
        // The scene is really there: the centre is the lit sphere, not the background.
        REQUIRE(std::memcmp(image.at(w / 2, h / 2), image.at(1, 1), 3) != 0);
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("scene renderer: updateMesh in place draws what a fresh upload of the moved mesh draws")
{
    const int size = 64;
    const Mesh sphere = makeIcosphere(1.0, 3);
    Mesh moved = sphere;
    moved.V.col(0).array() += 0.6;
    moved.V.col(1).array() *= 0.8;
    const Camera camera = frameSphere({ 0, 0, 0 }, 2.0, { 0, 0 }, size, size);

    Renderer fresh(test::device(), size, size, 1);
    fresh.addMesh(moved);
    const Image expected = fresh.render(camera);

    // Two slots, as a window has: each slot's copy is brought up to date when it is recorded.
    SceneRenderer scene(test::device(), { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, 2);
    const DrawId id = scene.addMesh(sphere);
    const Image before0 = drawDynamic(scene, 0, camera, size, size, { 1, 1, 1, 1 });
    const Image before1 = drawDynamic(scene, 1, camera, size, size, { 1, 1, 1, 1 });
    REQUIRE(before0.pixels == before1.pixels);
    REQUIRE(before0.pixels != expected.pixels);
    scene.updateMesh(id, moved.V);
    const Image after1 = drawDynamic(scene, 1, camera, size, size, { 1, 1, 1, 1 });
    const Image after0 = drawDynamic(scene, 0, camera, size, size, { 1, 1, 1, 1 });
    INFO(firstDifference(after1, expected));
    REQUIRE(after1.pixels == expected.pixels);
    REQUIRE(after0.pixels == expected.pixels);

    REQUIRE_THROWS_AS(scene.updateMesh(id, moved.V.topRows(10)), Error);
    Vertices bad = moved.V;
    bad(3, 1) = NAN;
    REQUIRE_THROWS_AS(scene.updateMesh(id, bad), Error);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("scene renderer: mesh colours change in place and hidden or removed items are not drawn")
{
    const int size = 48;
    const Mesh sphere = makeIcosphere(1.0, 2);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.0, { 0, 0 }, size, size);
    SceneRenderer scene(test::device(), { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, 1);
    const DrawId id = scene.addMesh(sphere, MeshStyle { { 1, 1, 1, 1 }, false });
    const std::uint8_t* centre = nullptr;
    Image image = drawDynamic(scene, 0, camera, size, size, { 0, 0, 0, 1 });
    centre = image.at(size / 2, size / 2);
    REQUIRE((centre[0] == 255 && centre[1] == 255 && centre[2] == 255));

    scene.setMeshColors(id, std::vector<glm::vec4>(sphere.V.rows(), glm::vec4(0, 1, 0, 1)));
    image = drawDynamic(scene, 0, camera, size, size, { 0, 0, 0, 1 });
    centre = image.at(size / 2, size / 2);
    REQUIRE((centre[0] == 0 && centre[1] == 255 && centre[2] == 0));

    scene.setVisible(id, false);
    image = drawDynamic(scene, 0, camera, size, size, { 0, 0, 0, 1 });
    centre = image.at(size / 2, size / 2);
    REQUIRE((centre[0] == 0 && centre[1] == 0 && centre[2] == 0));

    scene.setVisible(id, true);
    scene.remove(id);
    image = drawDynamic(scene, 0, camera, size, size, { 0, 0, 0, 1 });
    centre = image.at(size / 2, size / 2);
    REQUIRE((centre[0] == 0 && centre[1] == 0 && centre[2] == 0));
    REQUIRE_THROWS_AS(scene.setVisible(id, true), Error);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("scene renderer: an opaque mesh replaces what is behind it and a translucent one blends by its alpha")
{
    // Opaque meshes are drawn without blending; one vertex colour below alpha 1 switches the
    // mesh back to the blended pipeline, and opaque colours switch it back again.
    const int size = 48;
    const Mesh sphere = makeIcosphere(1.0, 2);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.0, { 0, 0 }, size, size);
    SceneRenderer scene(test::device(), { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, 1);
    const DrawId id = scene.addMesh(sphere, MeshStyle { { 1, 0, 0, 1 }, false });
    Image image = drawDynamic(scene, 0, camera, size, size, { 0, 0, 1, 1 });
    const std::uint8_t* centre = image.at(size / 2, size / 2);
    REQUIRE((centre[0] == 255 && centre[1] == 0 && centre[2] == 0 && centre[3] == 255));

    scene.setMeshColors(id, std::vector<glm::vec4>(sphere.V.rows(), glm::vec4(1, 0, 0, 0.5f)));
    image = drawDynamic(scene, 0, camera, size, size, { 0, 0, 1, 1 });
    centre = image.at(size / 2, size / 2);
    // 0.5 red over blue: half of each (unorm rounding), alpha 0.5 + 1 * 0.5 = 1.
    REQUIRE((std::abs(int(centre[0]) - 128) <= 1 && centre[1] == 0 && std::abs(int(centre[2]) - 128) <= 1 && centre[3] == 255));

    scene.setMeshColors(id, {});
    image = drawDynamic(scene, 0, camera, size, size, { 0, 0, 1, 1 });
    centre = image.at(size / 2, size / 2);
    REQUIRE((centre[0] == 255 && centre[1] == 0 && centre[2] == 0 && centre[3] == 255));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("scene renderer: the overlay blends by its alpha as the CPU computes it, row 0 at the top")
{
    const int w = 40, h = 30;
    const glm::vec4 background { 0.2f, 0.4f, 0.6f, 1.0f };
    SceneRenderer scene(test::device(), { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, 1);
    // 2 x 2 texels stretched over the viewport: one per quadrant.
    Image overlay;
    overlay.width = 2;
    overlay.height = 2;
    overlay.pixels = { 200, 50, 100, 64, /**/ 0, 0, 0, 0, /**/ 10, 250, 30, 255, /**/ 255, 255, 255, 128 };
    scene.setOverlay(overlay);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.0, { 0, 0 }, w, h);
    const Image image = drawDynamic(scene, 0, camera, w, h, background);

    auto expect = [&](int x, int y, const std::uint8_t* texel) {
        const double a = texel[3] / 255.0;
        for (int c = 0; c < 3; ++c) {
            const double reference = 255.0 * (texel[c] / 255.0 * a + background[c] * (1 - a));
            INFO("pixel (" << x << ", " << y << ") channel " << c << ": " << int(image.at(x, y)[c]) << " vs " << reference);
            // One step of 8-bit rounding: the blend runs in float, the attachment stores 8 bits.
            REQUIRE(std::abs(image.at(x, y)[c] - reference) <= 1.0);
        }
    };
    expect(5, 5, &overlay.pixels[0]);          // top-left
    expect(w - 5, 5, &overlay.pixels[4]);      // top-right: alpha 0 leaves the background
    expect(5, h - 5, &overlay.pixels[8]);      // bottom-left: opaque
    expect(w - 5, h - 5, &overlay.pixels[12]); // bottom-right
    REQUIRE(image.at(w - 5, 5)[2] == std::uint8_t(std::lround(0.6 * 255)));

    // Cleared: the background alone.
    scene.clearOverlay();
    const Image cleared = drawDynamic(scene, 0, camera, w, h, background);
    REQUIRE(cleared.at(5, 5)[0] == std::uint8_t(std::lround(0.2 * 255)));
    REQUIRE_THROWS_AS(scene.setOverlay(Image {}), Error);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("scene renderer: a screen polyline lands on its pixels, over a mesh, after the overlay")
{
    const int size = 64;
    SceneRenderer scene(test::device(), { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, 1);
    scene.addMesh(makeIcosphere(1.0, 2), MeshStyle { { 0, 0, 1, 1 }, false });
    // Horizontal through the sphere at row 20, then down column 50: pixel centres at +0.5.
    const DrawId line = scene.addScreenPolyline({ { 4.5f, 20.5f }, { 50.5f, 20.5f }, { 50.5f, 60.5f } }, { { 1, 0, 0, 1 } });
    Image overlay;
    overlay.width = overlay.height = 1;
    overlay.pixels = { 0, 255, 0, 255 }; // opaque green over everything depth-tested
    scene.setOverlay(overlay);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.0, { 0, 0 }, size, size);
    Image image = drawDynamic(scene, 0, camera, size, size, { 1, 1, 1, 1 });
    auto is = [&](int x, int y, int r, int g, int b) {
        const std::uint8_t* p = image.at(x, y);
        return p[0] == r && p[1] == g && p[2] == b;
    };
    REQUIRE(is(32, 20, 255, 0, 0)); // over the sphere and the overlay
    REQUIRE(is(10, 20, 255, 0, 0));
    REQUIRE(is(50, 40, 255, 0, 0));
    REQUIRE(is(32, 22, 0, 255, 0)); // the overlay elsewhere
    REQUIRE(is(40, 40, 0, 255, 0));

    scene.setScreenPolyline(line, { { 4.5f, 40.5f }, { 30.5f, 40.5f } }, { { 0, 0, 0, 1 } });
    scene.clearOverlay();
    image = drawDynamic(scene, 0, camera, size, size, { 1, 1, 1, 1 });
    REQUIRE(is(10, 40, 0, 0, 0));
    REQUIRE(is(32, 20, 0, 0, 255)); // the sphere again
    REQUIRE_THROWS_AS(scene.setLines(line, {}, { { 1, 1, 1, 1 } }), Error);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("scene renderer: at a pixel scale, screen polylines in the caller's pixels land on the reduced target's pixels")
{
    // The app draws its view at half resolution while it moves; strokes are in window pixels.
    const int size = 64;
    SceneRenderer scene(test::device(), { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, 1);
    scene.addScreenPolyline({ { 8.5f, 40.5f }, { 100.5f, 40.5f }, { 100.5f, 120.5f } }, { { 1, 0, 0, 1 } });
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.0, { 0, 0 }, size, size);
    const Image full = drawDynamic(scene, 0, camera, 2 * size, 2 * size, { 1, 1, 1, 1 });
    const Image half = drawDynamic(scene, 0, camera, size, size, { 1, 1, 1, 1 }, 0.5f);
    auto red = [](const Image& image, int x, int y) {
        const std::uint8_t* p = image.at(x, y);
        return p[0] == 255 && p[1] == 0 && p[2] == 0;
    };
    REQUIRE(red(full, 60, 40));
    REQUIRE(red(full, 100, 80));
    REQUIRE_FALSE(red(full, 30, 20));
    // Half the coordinates: row 20 from column 4, then down column 50.
    REQUIRE(red(half, 30, 20));
    REQUIRE(red(half, 50, 40));
    REQUIRE_FALSE(red(half, 30, 40));
    REQUIRE_FALSE(red(half, 60, 20));
    int redPixels = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            redPixels += red(half, x, y);
    REQUIRE(redPixels >= 80); // 46 + 40 pixels of one-pixel line, about
    REQUIRE(redPixels <= 92);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("scene renderer: an added one-sample target draws the items as a one-sample renderer does, the MSAA one unchanged")
{
    const RenderTargetFormat msaa { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 4 };
    const RenderTargetFormat single { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 };
    const Mesh sphere = makeIcosphere(1.0, 3);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.2, { 30, 10 }, 96, 80);
    SceneRenderer both(test::device(), msaa, 1);
    addTestScene(both, sphere);
    const std::uint32_t added = both.addTarget(single);
    REQUIRE(added == 1);
    SceneRenderer one(test::device(), single, 1), four(test::device(), msaa, 1);
    addTestScene(one, sphere);
    addTestScene(four, sphere);
    const glm::vec4 background { 0.9f, 0.9f, 0.95f, 1 };
    const Image viaAdded = drawDynamic(both, 0, camera, 96, 80, background, 1.0f, added, &single);
    const Image viaMain = drawDynamic(both, 0, camera, 96, 80, background);
    const Image expectedOne = drawDynamic(one, 0, camera, 96, 80, background);
    const Image expectedFour = drawDynamic(four, 0, camera, 96, 80, background);
    INFO(firstDifference(viaAdded, expectedOne));
    REQUIRE(viaAdded.pixels == expectedOne.pixels);
    INFO(firstDifference(viaMain, expectedFour));
    REQUIRE(viaMain.pixels == expectedFour.pixels);
    REQUIRE(viaAdded.pixels != viaMain.pixels); // MSAA edges differ
    REQUIRE_THROWS_AS(both.addTarget({ .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 2 }), Error);
    gpu::submitAndWait(test::device(), [&](VkCommandBuffer cmd) {
        REQUIRE_THROWS_AS(both.record(cmd, 0, camera, { 8, 8 }, 1.0f, 2), Error);
    });
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("scene renderer: bad arguments are errors before anything changes")
{
    gpu::Device& d = test::device();
    REQUIRE_THROWS_AS(SceneRenderer(d, { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 2 }, 1), Error);
    REQUIRE_THROWS_AS(SceneRenderer(d, { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, 0), Error);
    SceneRenderer scene(d, { .color = VK_FORMAT_R8G8B8A8_UNORM, .depth = VK_FORMAT_D32_SFLOAT, .samples = 1 }, 2);
    const DrawId lines = scene.addLines({ { 0, 0, 0 }, { 1, 0, 0 } }, { { 1, 1, 1, 1 } });
    REQUIRE_THROWS_AS(scene.addLines({ { 0, 0, 0 } }, { { 1, 1, 1, 1 } }), Error);
    REQUIRE_THROWS_AS(scene.setLines(lines, { { 0, 0, 0 }, { 1, 0, 0 } }, { { 1, 1, 1, 1 }, { 1, 1, 1, 1 }, { 1, 1, 1, 1 } }), Error);
    REQUIRE_THROWS_AS(scene.updateMesh(lines, Vertices(2, 3)), Error);
    REQUIRE_THROWS_AS(scene.addPoints({ { 0, 0, 0 } }, { { 1, 1, 1, 1 } }, 0.0f), Error);
    REQUIRE_THROWS_AS(scene.remove(12345), Error);
    gpu::submitAndWait(d, [&](VkCommandBuffer cmd) { REQUIRE_THROWS_AS(scene.record(cmd, 2, Camera {}, { 8, 8 }), Error); });
    for (float scale : { 0.0f, 1.5f, std::nanf("") })
        gpu::submitAndWait(d, [&](VkCommandBuffer cmd) { REQUIRE_THROWS_AS(scene.record(cmd, 0, Camera {}, { 8, 8 }, scale), Error); });
    REQUIRE_NO_VALIDATION_MESSAGES();
}

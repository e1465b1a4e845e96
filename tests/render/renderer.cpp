#include "render/renderer.h"
#include "core/error.h"
#include "geometry/primitives.h"
#include "io/png.h"
#include "render/colormap.h"
#include "test_common.h"

#include <cmath>

using namespace facesketch;

static bool isBackground(const std::uint8_t* p)
{
    return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

static int luminance(const std::uint8_t* p)
{
    return (p[0] + p[1] + p[2]) / 3;
}

TEST_CASE("renderer: an orthographic unit sphere covers its predicted disc within 1%")
{
    const int size = 256;
    const double margin = 0.25;
    const Mesh sphere = makeIcosphere(1.0, 5);
    Renderer renderer(test::device(), size, size, 4);
    renderer.addMesh(sphere);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.0, parseView("front"), size, size, Projection::Orthographic, margin);
    const Image image = renderer.render(camera);
    // Coverage counts MSAA-resolved pixels more than half covered (partially covered edge
    // pixels blend towards white).
    const double radiusPx = size / 2.0 / (1.0 + margin);
    const double predicted = M_PI * radiusPx * radiusPx;
    long covered = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            covered += luminance(image.at(x, y)) < 230;
    INFO("covered " << covered << " predicted " << predicted);
    REQUIRE(std::abs(covered - predicted) / predicted < 0.01);

    // The disc is centred, and pixels outside its radius are background.
    REQUIRE(!isBackground(image.at(size / 2, size / 2)));
    REQUIRE(isBackground(image.at(size / 2, static_cast<int>(size / 2 - radiusPx - 3))));
    REQUIRE(isBackground(image.at(static_cast<int>(size / 2 + radiusPx + 3), size / 2)));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("renderer: the head light makes the sphere's centre brighter than its rim")
{
    const int size = 128;
    Renderer renderer(test::device(), size, size, 1);
    renderer.addMesh(makeIcosphere(1.0, 4));
    const Image image = renderer.render(frameSphere({ 0, 0, 0 }, 1.0, { 0, 0 }, size, size, Projection::Orthographic, 0.1));
    const double r = size / 2.0 / 1.1;
    const int centre = luminance(image.at(size / 2, size / 2));
    const int rim = luminance(image.at(size / 2, static_cast<int>(size / 2 + 0.97 * r)));
    INFO("centre " << centre << " rim " << rim);
    REQUIRE(centre > rim + 60); // front faces lit: a flipped winding or normal would invert this
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("renderer: camera conventions put +y at the top and, from the front, +x on the right")
{
    const int size = 64;
    Renderer renderer(test::device(), size, size, 1);
    renderer.addPoints({ { 0, 0.8f, 0 }, { 0.8f, 0, 0 } }, { { 1, 0, 0, 1 }, { 0, 0, 1, 1 } }, 5.0f);
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.0, parseView("front"), size, size);
    const Image image = renderer.render(camera);
    const glm::dvec3 top = camera.project({ 0, 0.8, 0 }), right = camera.project({ 0.8, 0, 0 });
    REQUIRE(top.y < size / 2.0);
    REQUIRE(right.x > size / 2.0);
    const std::uint8_t* red = image.at(int(top.x), int(top.y));
    const std::uint8_t* blue = image.at(int(right.x), int(right.y));
    REQUIRE((red[0] == 255 && red[1] == 0 && red[2] == 0));
    REQUIRE((blue[0] == 0 && blue[1] == 0 && blue[2] == 255));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("renderer: lines are drawn where the camera projects them")
{
    const int size = 64;
    Renderer renderer(test::device(), size, size, 1);
    renderer.addLines({ { -0.9f, 0.5f, 0 }, { 0.9f, 0.5f, 0 } }, { { 0, 1, 0, 1 } });
    const Camera camera = frameSphere({ 0, 0, 0 }, 1.0, { 0, 0 }, size, size);
    const Image image = renderer.render(camera);
    const glm::dvec3 a = camera.project({ -0.5, 0.5, 0 }), b = camera.project({ 0.5, 0.5, 0 });
    int green = 0;
    for (int x = int(a.x); x <= int(b.x); ++x)
        for (int dy = -1; dy <= 1; ++dy) {
            const std::uint8_t* p = image.at(x, int(a.y) + dy);
            green += p[0] == 0 && p[1] == 255 && p[2] == 0;
        }
    REQUIRE(green >= int(b.x) - int(a.x)); // one green pixel per column
    REQUIRE(isBackground(image.at(size / 2, size / 2 + 10)));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("renderer: bad sizes and mismatched cameras are errors")
{
    REQUIRE_THROWS_AS(Renderer(test::device(), 0, 10), Error);
    REQUIRE_THROWS_AS(Renderer(test::device(), 10, 10, 2), Error);
    Renderer renderer(test::device(), 32, 32, 1);
    REQUIRE_THROWS_WITH(renderer.render(frameSphere({ 0, 0, 0 }, 1, { 0, 0 }, 64, 64)), Catch::Contains("camera is 64x64"));
    REQUIRE_THROWS_AS(renderer.addLines({ { 0, 0, 0 } }, { { 1, 1, 1, 1 } }), Error);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("colormap: blue at 0, green at 0.5, red at 1, clamped outside")
{
    REQUIRE(blueToRed(0.0) == glm::vec4(0, 0, 1, 1));
    REQUIRE(blueToRed(0.5) == glm::vec4(0, 1, 0, 1));
    REQUIRE(blueToRed(1.0) == glm::vec4(1, 0, 0, 1));
    REQUIRE(blueToRed(-3.0) == blueToRed(0.0));
    REQUIRE(blueToRed(7.0) == blueToRed(1.0));
    REQUIRE(blueToRed(0.125) == glm::vec4(0, 0.5f, 1, 1));
    REQUIRE(blueToRed(0.75) == glm::vec4(1, 1, 0, 1));
}

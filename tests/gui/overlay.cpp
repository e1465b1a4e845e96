// The sketchability overlay: the heat image of candidate positions and the cloud of a view.
#include "gui/overlay.h"

#include "core/error.h"
#include "fixture.h"
#include "test_common.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::gui;

namespace {

int alphaAt(const Image& image, int x, int y)
{
    return image.pixels[(static_cast<size_t>(y) * image.width + x) * 4 + 3];
}

Candidate at(float x, float y)
{
    Candidate c;
    c.screen[0] = x;
    c.screen[1] = y;
    return c;
}

} // namespace

TEST_CASE("overlay: the heat image is hot where candidates crowd and clear where there are none")
{
    std::vector<Candidate> cloud;
    for (int i = 0; i < 20; ++i)
        cloud.push_back(at(40.5f + static_cast<float>(i % 5), 30.5f + static_cast<float>(i / 10)));
    cloud.push_back(at(150, 90)); // one lone candidate
    cloud.push_back(at(-5, 10));  // off the image: ignored
    const Image image = heatImage(cloud, 200, 120);
    REQUIRE(image.width == 200);
    REQUIRE(image.pixels.size() == 200u * 120 * 4);
    const std::uint8_t* hot = &image.pixels[(32u * 200 + 42) * 4];
    REQUIRE(hot[0] > 200); // red at the peak
    REQUIRE(hot[2] < 50);
    int peak = 0;
    for (size_t i = 3; i < image.pixels.size(); i += 4)
        peak = std::max(peak, static_cast<int>(image.pixels[i]));
    REQUIRE(peak == Approx(255 * 0.7).margin(1));
    REQUIRE(alphaAt(image, 42, 32) > 0.8 * peak);
    REQUIRE(alphaAt(image, 150, 90) > 0); // the lone one shows, faintly and blue
    REQUIRE(alphaAt(image, 150, 90) < alphaAt(image, 42, 32));
    REQUIRE(image.pixels[(90u * 200 + 150) * 4 + 2] > image.pixels[(90u * 200 + 150) * 4]);
    REQUIRE(alphaAt(image, 100, 60) == 0);
    REQUIRE(alphaAt(image, 0, 10) == 0);

    const Image empty = heatImage({}, 10, 10);
    REQUIRE(std::all_of(empty.pixels.begin(), empty.pixels.end(), [](std::uint8_t b) { return b == 0; }));
    REQUIRE_THROWS_WITH(heatImage({}, 0, 10), Catch::Contains("0x10"));
    HeatOptions bad;
    bad.cellPx = 0;
    REQUIRE_THROWS_AS(heatImage({}, 10, 10, bad), Error);
}

TEST_CASE("overlay: the candidate cloud of a front view lies on the faces, and its heat covers the face")
{
    const auto& w = test::sketchWorld();
    CandidateCloud cloud(test::device(), w.candidateFaces, w.flags, {});
    REQUIRE(cloud.faces() == static_cast<int>(w.candidateFaces.size()));
    const Camera camera = frameMesh(w.mean, { 0, 0 }, 320, 240);
    const std::vector<Candidate> c = cloud.candidates(camera);
    REQUIRE(c.size() > 100);
    int inside = 0;
    for (const Candidate& k : c) {
        REQUIRE(k.screen[0] >= 0);
        REQUIRE(k.screen[0] <= 319);
        const glm::dvec3 p = camera.project({ k.world[0], k.world[1], k.world[2] });
        REQUIRE(p.x == Approx(k.screen[0]).margin(0.05));
        inside += p.x > 60 && p.x < 260 ? 1 : 0;
    }
    REQUIRE(inside > static_cast<int>(c.size()) / 2);
    const Image heat = heatImage(c, 320, 240);
    // The image's corners are background: no candidate, no heat.
    REQUIRE(alphaAt(heat, 2, 2) == 0);
    REQUIRE(alphaAt(heat, 317, 237) == 0);
    int covered = 0;
    for (size_t i = 3; i < heat.pixels.size(); i += 4)
        covered += heat.pixels[i] > 0 ? 1 : 0;
    REQUIRE(covered > 320 * 240 / 20);
    REQUIRE_THROWS_WITH(CandidateCloud(test::device(), {}, {}, {}), Catch::Contains("no candidate faces"));
}

#include "sketch/stroke_candidates.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::sketch;

namespace {
Candidate at(const Camera& camera, double x, double y, double z, std::uint32_t vertex)
{
    Candidate c;
    c.vertex = vertex;
    c.world[0] = static_cast<float>(x);
    c.world[1] = static_cast<float>(y);
    c.world[2] = static_cast<float>(z);
    const glm::dvec3 s = camera.project({ x, y, z });
    c.screen[0] = static_cast<float>(s.x);
    c.screen[1] = static_cast<float>(s.y);
    c.depth = static_cast<float>(s.z);
    return c;
}
} // namespace

TEST_CASE("stroke_candidates: per point, candidates within the radius and depth tolerance, nearest first, at most the cap")
{
    const Camera camera = orbitCamera(frameSphereView({ 0, 0, 0 }, 100, { 0, 0 }, 400, 400));
    const double ppmm = pixelsPerMm(camera, Eigen::Vector3d::Zero());
    CHECK(ppmm == Approx(200.0 / 1.05 / 100.0).epsilon(1e-9));
    // Candidates along x at z = 0, one behind at z = -60, one far to the side.
    std::vector<Candidate> cloud;
    for (int i = 0; i < 5; ++i)
        cloud.push_back(at(camera, 2.0 * i, 0, 0, static_cast<std::uint32_t>(i)));
    cloud.push_back(at(camera, 0, 0, -60, 10));
    cloud.push_back(at(camera, 60, 0, 0, 11));
    const std::vector<Eigen::Vector2d> screen = { Eigen::Vector2d(cloud[0].screen[0], cloud[0].screen[1]), Eigen::Vector2d(0, 0) };
    const std::vector<Eigen::Vector3d> world = { Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(-100, 100, 0) };
    const double radius = 5.0 * ppmm; // 5 mm: candidates 0, 1, 2 (0, 2, 4 mm away) and 10 by screen
    const auto sets = candidatesPerPoint(cloud, camera, screen, world, radius, 40.0, 10);
    CHECK(sets[0] == std::vector<int> { 0, 1, 2 }); // 10 lies 60 mm behind: culled by depth
    CHECK(sets[1].empty());
    CHECK(candidatesPerPoint(cloud, camera, screen, world, radius, 100.0, 10)[0] == std::vector<int> { 0, 5, 1, 2 }); // ties: lower index
    CHECK(candidatesPerPoint(cloud, camera, screen, world, radius, 100.0, 2)[0] == std::vector<int> { 0, 5 });
}

TEST_CASE("stroke_candidates: the stroke box covers the on-screen points widened by the radius and skips far-off ones")
{
    const Camera camera = orbitCamera(frameSphereView({ 0, 0, 0 }, 100, { 0, 0 }, 400, 400));
    ContourParams p;
    const std::vector<Eigen::Vector2d> screen = { { 100, 120 }, { 150, 90 }, { -1e6, 0 } };
    const std::vector<Eigen::Vector3d> world = { { -10, 0, 5 }, { 10, 0, -5 }, { 1e6, 0, 0 } };
    REQUIRE(strokeBox(p, camera, screen, world, 10.0, 3.0));
    CHECK(p.rect[0] == 90);
    CHECK(p.rect[1] == 80);
    CHECK(p.rect[2] == 160);
    CHECK(p.rect[3] == 130);
    CHECK(p.sphere[0] == 0);
    CHECK(p.sphere[3] == Approx(0.5 * std::sqrt(400.0 + 100.0) + 3.0));
    ContourParams untouched;
    CHECK_FALSE(strokeBox(untouched, camera, { { -1e6, 0 } }, { { 0, 0, 0 } }, 10.0, 3.0));
    CHECK(untouched.rect[0] == ContourParams {}.rect[0]);
}

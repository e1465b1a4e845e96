#include "sketch/projection.h"

#include "core/error.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::sketch;

namespace {
// A square of side 100 mm in the plane z = zPlane, centred on the origin, two triangles facing +z.
Mesh square(double zPlane)
{
    Mesh m;
    m.V.resize(4, 3);
    m.V << -50, -50, zPlane, 50, -50, zPlane, 50, 50, zPlane, -50, 50, zPlane;
    m.F.resize(2, 3);
    m.F << 0, 1, 2, 0, 2, 3;
    return m;
}

Stroke strokeOf(std::vector<Eigen::Vector2d> points, ViewAngles angles, Surface surface)
{
    Stroke s;
    s.view = frameSphereView({ 0, 0, 0 }, 100, angles, 400, 300);
    s.surface = surface;
    for (const auto& p : points)
        s.points.push_back({ p.x(), p.y(), std::nullopt });
    return s;
}
} // namespace

TEST_CASE("projection: densify fills gaps along a cardinal spline and leaves far-off segments alone")
{
    const Eigen::Vector4d limit(-100, -100, 200, 200);
    std::vector<int> source;
    const auto out = densify({ { 0, 0 }, { 10, 0 }, { 11, 0 } }, 4.0, 0.0, limit, &source);
    REQUIRE(out.size() >= 5); // 10 px: at least 3 pieces; 1 px: none
    for (std::size_t i = 0; i + 1 < out.size(); ++i)
        CHECK((out[i + 1] - out[i]).norm() <= 4.0 + 1e-9);
    for (const auto& p : out)
        CHECK(p.y() == Approx(0).margin(1e-12)); // a straight stroke stays straight
    CHECK(source.size() == out.size());
    CHECK(source.front() == 0);
    CHECK(source[source.size() - 2] == 1);
    CHECK(source.back() == 2);
    // A curve: the new points leave the chord towards the neighbours' side.
    const auto bent = densify({ { 0, 10 }, { 10, 0 }, { 20, 0 }, { 30, 10 } }, 2.0, 0.0, limit);
    bool below = false;
    for (const auto& p : bent)
        below = below || (p.x() > 10 && p.x() < 20 && p.y() < -0.1);
    CHECK(below);
    // Tension 1 gives straight segments.
    for (const auto& p : densify({ { 0, 10 }, { 10, 0 }, { 20, 0 }, { 30, 10 } }, 2.0, 1.0, limit))
        if (p.x() > 10 && p.x() < 20)
            CHECK(p.y() == Approx(0).margin(1e-12));
    CHECK(densify({ { 0, 0 }, { 1e9, 0 } }, 4.0, 0.0, limit).size() == 2);
    REQUIRE_THROWS_WITH(densify({ { 0, 0 } }, 0.0, 0.0, limit), Catch::Contains("largest gap 0"));
}

TEST_CASE("projection: points cast on the face take its depth, misses are interpolated, planes give their depth")
{
    const Mesh face = square(10);
    // The sphere of radius 100 mm fills 300 px less the margin (1.43 px/mm): the square spans
    // about x 129..271 in the 400 px image.
    const Stroke s = strokeOf({ { 20, 150 }, { 150, 150 }, { 200, 150 }, { 250, 150 }, { 380, 150 } }, { 0, 0 }, Surface::Face);
    const Camera camera = orbitCamera(s.view);
    const ProjectedStroke p = projectStroke(s, camera, face, 1000.0, 0.0);
    REQUIRE(p.screen.size() == 5);
    CHECK(p.hits == 3);
    CHECK(p.hit == std::vector<char> { 0, 1, 1, 1, 0 });
    for (std::size_t i = 0; i < 5; ++i) {
        CHECK(p.world[i].z() == Approx(10).margin(1e-9)); // the misses take the hits' depth
        const glm::dvec3 back = camera.project(glm::dvec3(p.world[i].x(), p.world[i].y(), p.world[i].z()));
        CHECK(back.x == Approx(p.screen[i].x()).margin(1e-6));
        CHECK(back.y == Approx(p.screen[i].y()).margin(1e-6));
    }
    CHECK_FALSE(p.fellBackToPaper);

    // Over empty background: the paper plane through the face's centre.
    const Stroke off = strokeOf({ { 5, 5 }, { 30, 10 } }, { 0, 0 }, Surface::Face);
    const ProjectedStroke q = projectStroke(off, camera, face, 4.0, 0.0);
    CHECK(q.fellBackToPaper);
    CHECK(q.hits == 0);
    for (const auto& w : q.world)
        CHECK(w.z() == Approx(10).margin(1e-9));

    // The profile plane x = 0 seen from the three-quarter view.
    const Stroke side = strokeOf({ { 150, 100 }, { 250, 200 } }, { 45, 0 }, Surface::ProfilePlane);
    for (const auto& w : projectStroke(side, orbitCamera(side.view), face, 4.0, 0.0).world)
        CHECK(w.x() == Approx(0).margin(1e-9));
    // The front plane z = 10 from the front, and the paper plane.
    const Stroke front = strokeOf({ { 150, 100 }, { 250, 200 } }, { 30, 20 }, Surface::FrontPlane);
    for (const auto& w : projectStroke(front, orbitCamera(front.view), face, 4.0, 0.0).world)
        CHECK(w.z() == Approx(10).margin(1e-9));
    // Seen edge-on, a plane cannot give a depth: named.
    const Stroke edgeOn = strokeOf({ { 150, 100 } }, { 90, 0 }, Surface::FrontPlane);
    REQUIRE_THROWS_WITH(
        projectStroke(edgeOn, orbitCamera(edgeOn.view), face, 4.0, 0.0), Catch::Contains("front-plane") && Catch::Contains("edge-on"));
}

TEST_CASE("projection: unproject inverts Camera::project in orthographic and perspective views")
{
    for (Projection kind : { Projection::Orthographic, Projection::Perspective }) {
        const Camera camera = orbitCamera(frameSphereView({ 1, 2, 3 }, 80, { 30, -10 }, 320, 240, kind));
        const glm::dvec3 x(10, -20, 15);
        const glm::dvec3 s = camera.project(x);
        const Eigen::Vector3d back = unproject(camera, s.x, s.y, s.z);
        CHECK(back.x() == Approx(x.x).margin(1e-6));
        CHECK(back.y() == Approx(x.y).margin(1e-6));
        CHECK(back.z() == Approx(x.z).margin(1e-6));
    }
}

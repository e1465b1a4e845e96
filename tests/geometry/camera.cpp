#include "geometry/camera.h"
#include "core/error.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;

TEST_CASE("camera: parseView accepts names and angles, rejects the rest")
{
    REQUIRE(parseView("profile").azimuthDeg == 90);
    REQUIRE(parseView("34").azimuthDeg == 45);
    REQUIRE(parseView("-30,15").elevationDeg == 15);
    REQUIRE_THROWS_WITH(parseView("side"), Catch::Contains("view 'side'"));
    REQUIRE_THROWS_AS(parseView("10,100"), Error);
    REQUIRE_THROWS_AS(parseView("10,"), Error);
}

TEST_CASE("camera: orthographic framing puts the sphere's outline at the predicted radius")
{
    const Camera c = frameSphere({ 10, 20, 30 }, 5.0, parseView("front"), 200, 100, Projection::Orthographic, 0.25);
    const glm::dvec3 centre = c.project({ 10, 20, 30 });
    REQUIRE(centre.x == Approx(100.0));
    REQUIRE(centre.y == Approx(50.0));
    // The smaller side (100 px) spans the diameter plus the margin: radius 50 / 1.25 = 40 px.
    REQUIRE(c.project({ 15, 20, 30 }).x - centre.x == Approx(40.0));
    REQUIRE(c.project({ 10, 25, 30 }).y - centre.y == Approx(-40.0)); // +y is up on screen
    REQUIRE(glm::length(c.toCamera({ 0, 0, 0 }) - glm::dvec3(0, 0, 1)) < 1e-12);
}

TEST_CASE("camera: an orbit view moved away and back rebuilds the identical camera")
{
    for (Projection kind : { Projection::Orthographic, Projection::Perspective }) {
        const OrbitView framed = frameSphereView({ 1, 2, 3 }, 80.0, { 30, 10 }, 640, 480, kind);
        OrbitView moved = framed;
        moved.angles = { -120, -45 };
        moved.distance *= 2;
        OrbitView back = moved;
        back.angles = framed.angles;
        back.distance = framed.distance;
        const Camera a = orbitCamera(framed), b = orbitCamera(back);
        REQUIRE(a.view == b.view);
        REQUIRE(a.projection == b.projection);
        // The target projects to the viewport's centre and the eye sits `distance` from it.
        const glm::dvec3 centre = a.project({ 1, 2, 3 });
        REQUIRE(centre.x == Approx(320.0));
        REQUIRE(centre.y == Approx(240.0));
        REQUIRE(glm::length(a.eye - glm::dvec3(1, 2, 3)) == Approx(framed.distance));
    }
}

TEST_CASE("camera: orbitCamera names the bad field of an orbit view")
{
    OrbitView v = frameSphereView({ 0, 0, 0 }, 10.0, {}, 100, 100);
    OrbitView bad = v;
    bad.width = 0;
    REQUIRE_THROWS_WITH(orbitCamera(bad), Catch::Contains("viewport"));
    bad = v;
    bad.distance = std::nan("");
    REQUIRE_THROWS_WITH(orbitCamera(bad), Catch::Contains("distance"));
    bad = v;
    bad.farPlane = bad.nearPlane;
    REQUIRE_THROWS_WITH(orbitCamera(bad), Catch::Contains("near plane"));
    bad = v;
    bad.angles.elevationDeg = 91;
    REQUIRE_THROWS_WITH(orbitCamera(bad), Catch::Contains("elevation"));
    bad = v;
    bad.target.y = INFINITY;
    REQUIRE_THROWS_WITH(orbitCamera(bad), Catch::Contains("target"));
}

#include "core/error.h"
#include "geometry/camera.h"

#include <catch2/catch.hpp>

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
    const Camera c = frameSphere({10, 20, 30}, 5.0, parseView("front"), 200, 100, Projection::Orthographic, 0.25);
    const glm::dvec3 centre = c.project({10, 20, 30});
    REQUIRE(centre.x == Approx(100.0));
    REQUIRE(centre.y == Approx(50.0));
    // The smaller side (100 px) spans the diameter plus the margin: radius 50 / 1.25 = 40 px.
    REQUIRE(c.project({15, 20, 30}).x - centre.x == Approx(40.0));
    REQUIRE(c.project({10, 25, 30}).y - centre.y == Approx(-40.0)); // +y is up on screen
    REQUIRE(glm::length(c.toCamera({0, 0, 0}) - glm::dvec3(0, 0, 1)) < 1e-12);
}

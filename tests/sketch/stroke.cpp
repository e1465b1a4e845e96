#include "sketch/stroke.h"

#include "core/error.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;
using namespace facesketch::sketch;

namespace {
Stroke line(int n)
{
    Stroke s;
    s.view.width = s.view.height = 256;
    for (int i = 0; i < n; ++i)
        s.points.push_back({ 10.0 + i, 20.0, std::nullopt });
    return s;
}
} // namespace

TEST_CASE("stroke: surfaces round-trip through their names and unknown names are refused")
{
    for (Surface s : { Surface::Face, Surface::FrontPlane, Surface::ProfilePlane, Surface::Paper })
        CHECK(parseSurface(surfaceName(s)) == s);
    REQUIRE_THROWS_WITH(parseSurface("table"), Catch::Contains("'table'"));
}

TEST_CASE("stroke: validateStroke accepts one point, off-screen and zero-length strokes and names every bad field")
{
    CHECK_NOTHROW(validateStroke(line(1), "s"));
    Stroke far = line(3);
    far.points[1].x = -1e9;
    CHECK_NOTHROW(validateStroke(far, "s"));
    Stroke still = line(4);
    for (auto& p : still.points)
        p = { 5, 5, std::nullopt };
    CHECK_NOTHROW(validateStroke(still, "s"));

    REQUIRE_THROWS_WITH(validateStroke(line(0), "s"), Catch::Contains("s: the stroke has no points"));
    Stroke nan = line(5);
    nan.points[3].y = std::nan("");
    REQUIRE_THROWS_WITH(validateStroke(nan, "s"), Catch::Contains("point 3 has y = nan"));
    Stroke inf = line(5);
    inf.points[2].x = INFINITY;
    REQUIRE_THROWS_WITH(validateStroke(inf, "s"), Catch::Contains("point 2 has x = inf"));
    Stroke time = line(4);
    time.points[0].timeMs = 10;
    time.points[2].timeMs = 5; // point 1 has no time: compared with point 0's
    REQUIRE_THROWS_WITH(validateStroke(time, "s"), Catch::Contains("point 2 has time 5 ms, before point 0's 10 ms"));
    Stroke badTime = line(2);
    badTime.points[1].timeMs = NAN;
    REQUIRE_THROWS_WITH(validateStroke(badTime, "s"), Catch::Contains("point 1 has time nan"));
    Stroke view = line(2);
    view.view.width = 0;
    REQUIRE_THROWS_WITH(validateStroke(view, "s"), Catch::Contains("s: orbit view: viewport 0x256"));
}

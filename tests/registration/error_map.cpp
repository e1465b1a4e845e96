// Tests of registration/error_map: distances to a known surface, the summary and the colours.
#include "registration/error_map.h"

#include "core/error.h"
#include "geometry/primitives.h"
#include "registration/surface_query.h"
#include "render/colormap.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;
using namespace facesketch::registration;

TEST_CASE("distanceToSurface: heights over a patch, NaN beside it")
{
    const SurfaceQuery patch(makeGrid(5, 5, 10.0, 10.0));
    Vertices V(3, 3);
    V << 1, 2, 0.5, -3, 4, -2, 9, 0, 1;
    const std::vector<double> d = distanceToSurface(V, patch);
    REQUIRE(d[0] == Approx(0.5));
    REQUIRE(d[1] == Approx(2.0));
    REQUIRE(std::isnan(d[2]));
}

TEST_CASE("summarize: mean, nearest-rank 95th percentile and max of the finite values")
{
    std::vector<double> d;
    for (int i = 1; i <= 100; ++i)
        d.push_back(i * 0.1);
    d.push_back(std::nan(""));
    const ErrorSummary s = summarize(d);
    REQUIRE(s.measured == 100);
    REQUIRE(s.mean == Approx(5.05));
    REQUIRE(s.p95 == Approx(9.5));
    REQUIRE(s.max == Approx(10.0));
    REQUIRE(summarize({ std::nan("") }).measured == 0);
}

TEST_CASE("errorColors: blue at 0, red at the top of the scale, grey for no surface")
{
    const auto c = errorColors({ 0.0, 2.0, 4.0, std::nan("") }, 2.0);
    REQUIRE(c[0] == blueToRed(0.0));
    REQUIRE(c[1] == blueToRed(1.0));
    REQUIRE(c[2] == blueToRed(1.0));
    REQUIRE(c[3] == glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    REQUIRE(c[1] != c[0]);
    REQUIRE_THROWS_AS(errorColors({ 1.0 }, 0.0), Error);
}

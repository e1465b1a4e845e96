// Tests of render/colormap: the ramp's stops, monotone channels between them, and clamping.
#include "render/colormap.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using namespace facesketch;

namespace {

bool same(const glm::vec4& a, const glm::vec4& b)
{
    return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a;
}

} // namespace

TEST_CASE("colormap: the stops are blue, cyan, green, yellow and red")
{
    CHECK(same(blueToRed(0.0), { 0, 0, 1, 1 }));
    CHECK(same(blueToRed(0.25), { 0, 1, 1, 1 }));
    CHECK(same(blueToRed(0.5), { 0, 1, 0, 1 }));
    CHECK(same(blueToRed(0.75), { 1, 1, 0, 1 }));
    CHECK(same(blueToRed(1.0), { 1, 0, 0, 1 }));
    // Half way between two stops is their mean.
    CHECK(same(blueToRed(0.125), { 0, 0.5f, 1, 1 }));
    CHECK(same(blueToRed(0.875), { 1, 0.5f, 0, 1 }));
}

TEST_CASE("colormap: each channel moves one way between stops and the ramp is continuous")
{
    // Over [0, 1]: blue falls from 0.25 to 0.5, red rises from 0.5 to 0.75, green rises to
    // 0.25 and falls from 0.75; alpha is always 1.
    glm::vec4 previous = blueToRed(0.0);
    for (int i = 1; i <= 1000; ++i) {
        const double t = i / 1000.0;
        const glm::vec4 c = blueToRed(t);
        INFO("t = " << t);
        CHECK(c.a == 1.0f);
        CHECK((t <= 0.25 ? c.b == 1.0f : c.b <= previous.b));
        CHECK((t <= 0.5 ? c.r == 0.0f : c.r >= previous.r));
        CHECK((t <= 0.25 ? c.g >= previous.g : t <= 0.75 ? c.g == 1.0f : c.g <= previous.g));
        // One step of 0.001 moves a channel by 0.004 at most.
        CHECK(std::abs(c.r - previous.r) <= 0.0041f);
        CHECK(std::abs(c.g - previous.g) <= 0.0041f);
        CHECK(std::abs(c.b - previous.b) <= 0.0041f);
        previous = c;
    }
}

TEST_CASE("colormap: values outside 0 to 1 are clamped, non-finite values are the low end")
{
    CHECK(same(blueToRed(-3.0), blueToRed(0.0)));
    CHECK(same(blueToRed(7.5), blueToRed(1.0)));
    CHECK(same(blueToRed(std::numeric_limits<double>::infinity()), blueToRed(0.0)));
    CHECK(same(blueToRed(-std::numeric_limits<double>::infinity()), blueToRed(0.0)));
    CHECK(same(blueToRed(std::numeric_limits<double>::quiet_NaN()), blueToRed(0.0)));
}

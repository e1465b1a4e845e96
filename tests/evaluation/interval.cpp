// Tests of evaluation/interval: the bootstrap interval of a ratio of means against cases with a
// known answer (equal ratios, one face), its coverage of a known true ratio over many
// independent draws, its width falling as the faces grow in number, determinism, bad input; and
// the paired difference of two ratios over the same faces.
#include "evaluation/interval.h"

#include "core/error.h"
#include "core/random.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;
using namespace facesketch::evaluation;

namespace {

// n faces whose mean-face errors are uniform in [4, 7] mm and whose reconstruction errors are
// that times a ratio drawn from N(0.5, 0.15^2): the true ratio of the means is 0.5 (the
// numerator's mean is E[ratio] E[denominator], the two drawn independently).
void drawFaces(Random& random, size_t n, std::vector<double>& a, std::vector<double>& b)
{
    a.clear();
    b.clear();
    for (size_t i = 0; i < n; ++i) {
        b.push_back(random.uniform(4, 7));
        a.push_back(b.back() * (0.5 + 0.15 * random.normal()));
    }
}

} // namespace

TEST_CASE("interval: faces that all have one ratio give that ratio at both ends, and one face gives its own")
{
    const std::vector<double> b { 4.0, 5.5, 6.25, 3.0 }, a { 2.0, 2.75, 3.125, 1.5 };
    const Interval i = bootstrapRatio(a, b);
    REQUIRE(i.low == Approx(0.5).epsilon(1e-12));
    REQUIRE(i.high == Approx(0.5).epsilon(1e-12));
    const Interval one = bootstrapRatio({ 3.0 }, { 5.0 });
    REQUIRE(one.low == Approx(0.6).epsilon(1e-12));
    REQUIRE(one.high == Approx(0.6).epsilon(1e-12));
}

TEST_CASE("interval: the 95% interval of 20 faces covers the true ratio in about 95% of independent draws")
{
    // The percentile bootstrap undercovers a little for small samples; over 400 draws the
    // binomial standard error of 95% is 1.1%, so 0.90 - 0.99 holds for a working interval, while
    // one that ignored the spread (a point) or took vertices for faces would cover far less.
    Random random(7);
    std::vector<double> a, b;
    int covered = 0;
    const int draws = 400;
    double lowSum = 0, highSum = 0;
    for (int d = 0; d < draws; ++d) {
        drawFaces(random, 20, a, b);
        const Interval i = bootstrapRatio(a, b, 1000, static_cast<std::uint64_t>(d) + 1);
        REQUIRE(i.low <= i.high);
        covered += i.low <= 0.5 && 0.5 <= i.high;
        lowSum += i.low;
        highSum += i.high;
    }
    const double coverage = static_cast<double>(covered) / draws;
    INFO("coverage " << coverage << ", mean interval " << lowSum / draws << " .. " << highSum / draws);
    REQUIRE(coverage > 0.90);
    REQUIRE(coverage < 0.99);
    // Its width: about 2 x 1.96 x 0.15 / sqrt(20) = 0.13 (the ratio's spread over the faces).
    REQUIRE((highSum - lowSum) / draws == Approx(0.13).margin(0.025));
}

TEST_CASE("interval: four times the faces halve the interval's width")
{
    Random random(11);
    std::vector<double> a, b;
    double w20 = 0, w80 = 0;
    for (int d = 0; d < 50; ++d) {
        drawFaces(random, 20, a, b);
        const Interval i20 = bootstrapRatio(a, b);
        w20 += i20.high - i20.low;
        drawFaces(random, 80, a, b);
        const Interval i80 = bootstrapRatio(a, b);
        w80 += i80.high - i80.low;
    }
    INFO("mean widths " << w20 / 50 << " (20 faces), " << w80 / 50 << " (80 faces)");
    REQUIRE(w80 / w20 == Approx(0.5).margin(0.06));
}

TEST_CASE("interval: a seed names one interval")
{
    Random random(3);
    std::vector<double> a, b;
    drawFaces(random, 20, a, b);
    const Interval x = bootstrapRatio(a, b, 2000, 5), y = bootstrapRatio(a, b, 2000, 5), z = bootstrapRatio(a, b, 2000, 6);
    REQUIRE(x.low == y.low);
    REQUIRE(x.high == y.high);
    REQUIRE(x.low != z.low);
}

TEST_CASE("interval: paired on the same faces, a difference far inside both ratios' intervals is certain, and covered")
{
    // Two mappers on the same 20 faces: the second rebuilds each face 0.03 of its mean-face
    // error better, give or take 0.01; which faces are hard is shared (spread 0.15). The true
    // difference of the ratios is -0.03. Each ratio's own interval is about 0.13 wide, so the
    // two overlap; the paired one is about 2 x 1.96 x 0.01 / sqrt(20) = 0.009 wide, under 0.
    Random random(13);
    int covered = 0, certain = 0, overlapping = 0;
    const int draws = 400;
    double width = 0;
    for (int d = 0; d < draws; ++d) {
        std::vector<double> first, denominators, second;
        drawFaces(random, 20, first, denominators);
        for (size_t i = 0; i < first.size(); ++i)
            second.push_back(first[i] + denominators[i] * (-0.03 + 0.01 * random.normal()));
        const Interval p = bootstrapRatioDifference(second, first, denominators, 1000, static_cast<std::uint64_t>(d) + 1);
        const Interval i1 = bootstrapRatio(first, denominators, 1000, 1), i2 = bootstrapRatio(second, denominators, 1000, 1);
        REQUIRE(p.low <= p.high);
        covered += p.low <= -0.03 && -0.03 <= p.high;
        certain += p.high < 0;
        overlapping += i2.high > i1.low;
        width += p.high - p.low;
    }
    INFO("coverage " << static_cast<double>(covered) / draws << ", certain " << certain << ", overlapping " << overlapping
                     << ", mean width " << width / draws);
    REQUIRE(covered > 0.90 * draws);
    REQUIRE(covered < 0.99 * draws);
    REQUIRE(certain == draws);
    REQUIRE(overlapping == draws);
    REQUIRE(width / draws == Approx(0.009).margin(0.002));

    // Swapped, the difference changes sign; the same faces with no difference give 0 at both ends.
    std::vector<double> a, b;
    drawFaces(random, 20, a, b);
    const Interval none = bootstrapRatioDifference(a, a, b);
    REQUIRE(none.low == 0);
    REQUIRE(none.high == 0);
    std::vector<double> c(a);
    for (size_t i = 0; i < c.size(); ++i)
        c[i] += 0.1 * b[i];
    const Interval up = bootstrapRatioDifference(c, a, b), down = bootstrapRatioDifference(a, c, b);
    REQUIRE(up.low == Approx(0.1).epsilon(1e-12));
    REQUIRE(up.high == Approx(0.1).epsilon(1e-12));
    REQUIRE(down.low == Approx(-0.1).epsilon(1e-12));
}

TEST_CASE("interval: bad input is refused with a message naming it")
{
    const auto throwsWith = [](const std::vector<double>& a, const std::vector<double>& b, int resamples, const char* text) {
        REQUIRE_THROWS_WITH(bootstrapRatio(a, b, resamples), Catch::Contains(text));
    };
    throwsWith({ 1, 2 }, { 3 }, 2000, "2 numerators but 1 denominators");
    throwsWith({}, {}, 2000, "no faces");
    throwsWith({ 1 }, { 2 }, 99, "99 resamples");
    throwsWith({ 1, std::nan("") }, { 2, 3 }, 2000, "face 1 has a value that is not finite");
    throwsWith({ 1, 2 }, { 2, INFINITY }, 2000, "face 1 has a value that is not finite");
    throwsWith({ 1, 2 }, { 2, -3 }, 2000, "face 1 has a negative denominator -3");
    throwsWith({ 1, 2 }, { 0, 0 }, 2000, "the denominators sum to 0");
    REQUIRE_THROWS_WITH(
        bootstrapRatioDifference({ 1, 2 }, { 1 }, { 3, 4 }), Catch::Contains("2 values of the first ratio but 1 of the second"));
    REQUIRE_THROWS_WITH(bootstrapRatioDifference({ 1, 2 }, { 1, 2 }, { 3 }), Catch::Contains("2 numerators but 1 denominators"));
    REQUIRE_THROWS_WITH(bootstrapRatioDifference({ 1, NAN }, { 1, 2 }, { 3, 4 }), Catch::Contains("face 1 has a value that is not finite"));
}

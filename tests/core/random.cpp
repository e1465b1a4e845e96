// Tests of core/random: the standard mt19937_64 stream, reproducible streams, the three
// Box-Muller conventions written out by hand, SplitMix64, and the moments of the samplers.
#include "core/random.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace facesketch;

TEST_CASE("random: the same seed gives the same numbers")
{
    Random a(42), b(42), c(43);
    const Eigen::MatrixXd A = a.normalMatrix(5, 7);
    REQUIRE(A == b.normalMatrix(5, 7));
    REQUIRE(A != c.normalMatrix(5, 7));
    REQUIRE(a.permutation(50) == b.permutation(50));
    // normalMatrix fills column by column from normal().
    Random d(42);
    for (Eigen::Index j = 0; j < 7; ++j)
        for (Eigen::Index i = 0; i < 5; ++i)
            REQUIRE(A(i, j) == d.normal());
}

TEST_CASE("random: uniform is the top 53 bits of the standard mt19937_64 stream")
{
    // mt19937_64's 10000th output for the default seed 5489 is fixed by the C++ standard.
    Random standard(5489u);
    double u = 0;
    for (int i = 0; i < 10000; ++i)
        u = standard.uniform();
    REQUIRE(u == static_cast<double>(9981545732273789042ull >> 11) * 0x1.0p-53);
    Random a(9), b(9);
    REQUIRE(a.uniform(-3.0, 5.0) == -3.0 + 8.0 * b.uniform());
}

TEST_CASE("random: splitMix64 matches the published reference outputs")
{
    // SplitMix64 seeded with 1234567 (state advanced before each output), the reference
    // sequence of Vigna's splitmix64.c: 6457827717110365317, 3203168211198807973, ...
    REQUIRE(splitMix64(1234567) == 6457827717110365317ull);
    REQUIRE(splitMix64(1234567 + 0x9E3779B97F4A7C15ull) == 3203168211198807973ull);
    REQUIRE(splitMix64(0) != splitMix64(1));
}

TEST_CASE("random: each Box-Muller convention turns the engine's bits into the stated pair")
{
    for (const BoxMuller kind : { BoxMuller::OneMinus, BoxMuller::RedrawZero, BoxMuller::PlusOne }) {
        Random random(77, kind);
        std::mt19937_64 engine(77);
        for (int pair = 0; pair < 50; ++pair) {
            const double k1 = static_cast<double>(engine() >> 11), k2 = static_cast<double>(engine() >> 11);
            // k1 = 0 has probability 2^-53: RedrawZero's redraw cannot be met in 50 pairs.
            REQUIRE(k1 > 0);
            const double u1 = kind == BoxMuller::OneMinus ? 1.0 - k1 * 0x1.0p-53
                : kind == BoxMuller::RedrawZero           ? k1 * 0x1.0p-53
                                                          : (k1 + 1) * 0x1.0p-53;
            const double u2 = kind == BoxMuller::PlusOne ? (k2 + 1) * 0x1.0p-53 : k2 * 0x1.0p-53;
            const double radius = std::sqrt(-2.0 * std::log(u1)), angle = 2.0 * std::numbers::pi * u2;
            REQUIRE(random.normal() == radius * std::cos(angle));
            REQUIRE(random.normal() == radius * std::sin(angle));
        }
    }
}

TEST_CASE("random: normal samples have mean 0 and variance 1")
{
    Random random(7);
    const int n = 200000;
    double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double x = random.normal();
        sum += x;
        sum2 += x * x;
        sum4 += x * x * x * x;
    }
    // Standard errors: 1/sqrt(n) for the mean, sqrt(2/n) for the variance, sqrt(96/n) for
    // the fourth moment; allow five of them.
    CHECK(std::abs(sum / n) < 5.0 / std::sqrt(n));
    CHECK(std::abs(sum2 / n - 1.0) < 5.0 * std::sqrt(2.0 / n));
    CHECK(std::abs(sum4 / n - 3.0) < 5.0 * std::sqrt(96.0 / n));
}

TEST_CASE("random: uniform stays below 1 and index covers its range evenly")
{
    Random random(3);
    std::vector<int> counts(7, 0);
    for (int i = 0; i < 70000; ++i) {
        const double u = random.uniform();
        REQUIRE(u >= 0.0);
        REQUIRE(u < 1.0);
        ++counts[static_cast<size_t>(random.index(7))];
    }
    // Each count is Binomial(70000, 1/7): mean 10000, sd ~ 93.
    for (int c : counts)
        CHECK(std::abs(c - 10000) < 500);
    std::vector<int> p = random.permutation(100);
    std::sort(p.begin(), p.end());
    for (int i = 0; i < 100; ++i)
        REQUIRE(p[static_cast<size_t>(i)] == i);
}

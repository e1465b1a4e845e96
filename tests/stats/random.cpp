// Tests of stats/random: reproducible streams and the moments of the samplers.
#include "stats/random.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch::stats;

TEST_CASE("random: the same seed gives the same numbers")
{
    Random a(42), b(42), c(43);
    const Eigen::MatrixXd A = a.normalMatrix(5, 7);
    REQUIRE(A == b.normalMatrix(5, 7));
    REQUIRE(A != c.normalMatrix(5, 7));
    REQUIRE(a.permutation(50) == b.permutation(50));
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

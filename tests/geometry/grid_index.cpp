#include "geometry/grid_index.h"

#include "core/error.h"
#include "core/random.h"

#include <algorithm>
#include <catch2/catch.hpp>

using namespace facesketch;

namespace {
std::vector<Eigen::Vector2d> randomPoints(int n, std::uint32_t seed, double extent)
{
    Random random(seed);
    auto u = [&] { return random.uniform(-extent, extent); };
    std::vector<Eigen::Vector2d> out;
    for (int i = 0; i < n; ++i)
        out.emplace_back(u(), u());
    return out;
}
} // namespace

TEST_CASE("grid_index: nearest and within-radius agree with brute force, queries inside and far outside")
{
    const auto points = randomPoints(500, 7, 100.0);
    for (double cell : { 0.5, 4.0, 50.0 }) {
        const GridIndex index(points, cell);
        const auto queries = randomPoints(200, 11, 400.0); // many outside the points' box
        for (const Eigen::Vector2d& q : queries) {
            int best = -1;
            double bestD2 = 0;
            for (std::size_t i = 0; i < points.size(); ++i) {
                const double d2 = (points[i] - q).squaredNorm();
                if (best < 0 || d2 < bestD2) {
                    best = static_cast<int>(i);
                    bestD2 = d2;
                }
            }
            INFO("cell " << cell << " query " << q.transpose());
            REQUIRE(index.nearest(q) == best);
            for (double r : { 0.0, 3.0, 30.0 }) {
                std::vector<int> expected;
                for (std::size_t i = 0; i < points.size(); ++i)
                    if ((points[i] - q).squaredNorm() <= r * r)
                        expected.push_back(static_cast<int>(i));
                REQUIRE(index.withinRadius(q, r) == expected);
                // The visitor sees the same points once each, with their squared distances.
                std::vector<int> visited;
                index.forEachWithinRadius(q, r, [&](int i, double d2) {
                    REQUIRE(d2 == (points[static_cast<std::size_t>(i)] - q).squaredNorm());
                    visited.push_back(i);
                });
                std::sort(visited.begin(), visited.end());
                REQUIRE(visited == expected);
            }
        }
    }
}

TEST_CASE("grid_index: ties go to the lowest index, empty sets answer nothing, bad input is named")
{
    const std::vector<Eigen::Vector2d> points = { { 5, 5 }, { 1, 1 }, { 1, 1 }, { -3, 1 } };
    const GridIndex index(points, 2.0);
    CHECK(index.nearest({ 1, 1 }) == 1);
    CHECK(index.nearest({ -1, 1 }) == 1); // (1, 1) and (-3, 1) are both 2 away: lowest index
    CHECK(index.withinRadius({ 1, 1 }, 0.0) == std::vector<int> { 1, 2 });

    const GridIndex empty({}, 1.0);
    CHECK(empty.nearest({ 0, 0 }) == -1);
    CHECK(empty.withinRadius({ 0, 0 }, 10).empty());

    // One point far away must not make a huge grid; queries anywhere still work.
    const GridIndex spread({ { 0, 0 }, { 1e12, -1e12 } }, 1.0);
    CHECK(spread.nearest({ 1, 1 }) == 0);
    CHECK(spread.nearest({ 1e12, -1e12 + 3 }) == 1);
    CHECK(spread.withinRadius({ 1e30, 0 }, 5).empty());

    REQUIRE_THROWS_WITH(GridIndex({ { 0, 0 }, { std::nan(""), 1 } }, 1.0), Catch::Contains("point 1"));
    REQUIRE_THROWS_WITH(GridIndex(points, 0.0), Catch::Contains("cell size 0"));
}

TEST_CASE("grid_index: the k nearest accepted points within a radius agree with brute force, cells of any size")
{
    // A dense cluster (thousands in a disc, like stacked contours) plus a sparse spread.
    auto points = randomPoints(3000, 21, 6.0);
    for (const Eigen::Vector2d& p : randomPoints(400, 22, 120.0))
        points.push_back(p);
    points.push_back(points[5]); // an exact duplicate: the tie goes to the lower index
    auto accept = [](int i) { return i % 3 != 1; };
    for (double cell : { 0.25, 1.0, 16.0 }) {
        const GridIndex index(points, cell);
        std::vector<std::pair<double, int>> found;
        for (const Eigen::Vector2d& q : randomPoints(150, 23, 200.0))
            for (double r : { 0.0, 2.0, 40.0 })
                for (std::size_t k : { std::size_t { 1 }, std::size_t { 48 }, std::size_t { 5000 } }) {
                    std::vector<std::pair<double, int>> expected;
                    for (std::size_t i = 0; i < points.size(); ++i) {
                        const double d2 = (points[i] - q).squaredNorm();
                        if (d2 <= r * r && accept(static_cast<int>(i)))
                            expected.push_back({ d2, static_cast<int>(i) });
                    }
                    std::sort(expected.begin(), expected.end());
                    expected.resize(std::min(expected.size(), k));
                    index.nearestWithin(q, r, k, accept, found);
                    INFO("cell " << cell << " query " << q.transpose() << " radius " << r << " k " << k);
                    REQUIRE(found == expected);
                }
        index.nearestWithin(
            points[5], 0.0, 2, [](int) { return true; }, found);
        REQUIRE(found.size() == 2);
        CHECK(found[0].second == 5);
        CHECK(found[1].second == static_cast<int>(points.size()) - 1);
    }
}

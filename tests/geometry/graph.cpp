#include "geometry/graph.h"

#include "core/error.h"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;

namespace {
// A strip of triangles over a w x h grid of vertices (vertex = y * w + x), each quad split
// along the same diagonal, so hop distances are known in closed form.
Triangles gridTriangles(int w, int h)
{
    std::vector<std::array<int, 3>> t;
    for (int y = 0; y + 1 < h; ++y)
        for (int x = 0; x + 1 < w; ++x) {
            const int a = y * w + x, b = a + 1, c = a + w, d = c + 1;
            t.push_back({ a, b, d });
            t.push_back({ a, d, c });
        }
    Triangles F(static_cast<Eigen::Index>(t.size()), 3);
    for (std::size_t i = 0; i < t.size(); ++i)
        F.row(static_cast<Eigen::Index>(i)) << t[i][0], t[i][1], t[i][2];
    return F;
}
} // namespace

TEST_CASE("graph: k-ring hop counts on a triangulated grid match the closed form and stop at k")
{
    const int w = 9, h = 7;
    const Triangles F = gridTriangles(w, h);
    for (int k : { 0, 1, 2, 4 }) {
        const RingDistances rings(F, w * h, k);
        REQUIRE(rings.rings() == k);
        for (int i = 0; i < w * h; ++i)
            for (int j = 0; j < w * h; ++j) {
                // Edges go along x, along y and along the (+1, +1) diagonal: the hop count is
                // max(|dx|, |dy|) when dx and dy have the same sign, else |dx| + |dy|.
                const int dx = j % w - i % w, dy = j / w - i / w;
                const int exact = (dx >= 0) == (dy >= 0) ? std::max(std::abs(dx), std::abs(dy)) : std::abs(dx) + std::abs(dy);
                INFO("k " << k << " from " << i << " to " << j);
                REQUIRE(rings.hops(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)) == (exact <= k ? exact : -1));
            }
    }
}

TEST_CASE("graph: hand-made fan, isolated vertices and bad input")
{
    // A fan around vertex 0 with rim 1..5 (open), and vertex 6 in no triangle.
    Triangles F(4, 3);
    F << 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5;
    const RingDistances rings(F, 7, 4);
    CHECK(rings.hops(0, 0) == 0);
    CHECK(rings.hops(0, 5) == 1);
    CHECK(rings.hops(1, 5) == 2); // through the centre
    CHECK(rings.hops(1, 3) == 2);
    CHECK(rings.hops(2, 3) == 1);
    CHECK(rings.hops(6, 6) == 0);
    CHECK(rings.hops(6, 0) == -1);
    CHECK(rings.hops(0, 99) == -1);
    CHECK(rings.entries() == 6 * 6 + 1); // 0..5 reach each other within 2 hops; 6 only itself
    REQUIRE_THROWS_WITH(RingDistances(F, 4, 4), Catch::Contains("triangle 2"));
    REQUIRE_THROWS_WITH(RingDistances(F, 7, -1), Catch::Contains("k = -1"));
}

TEST_CASE("graph: shortestPath follows the shorter side of a square and respects the vertex limit")
{
    // A unit square split by the diagonal 0-2, plus vertex 4 far off joined to 3 only.
    Vertices V(5, 3);
    V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 5, 0;
    Triangles F(3, 3);
    F << 0, 1, 2, 0, 2, 3, 3, 2, 4;
    const EdgeGraph g = buildEdgeGraph(V, F, 5);
    REQUIRE(g.adjacency[0].size() == 3);
    REQUIRE(g.adjacency[0][1].first == 2);
    REQUIRE(g.adjacency[0][1].second == Approx(std::sqrt(2.0)));
    REQUIRE(shortestPath(g, 0, 2) == std::vector<int> { 0, 2 }); // the diagonal, sqrt 2 < 2
    REQUIRE(shortestPath(g, 1, 4) == std::vector<int> { 1, 2, 4 });
    REQUIRE(shortestPath(g, 3, 3) == std::vector<int> { 3 });
    // Below a limit of 4, vertex 4 is not part of the graph; a vertex with no edge cannot be
    // reached.
    const EdgeGraph skin = buildEdgeGraph(V, F, 4);
    REQUIRE(skin.adjacency.size() == 4);
    REQUIRE_THROWS_WITH(shortestPath(skin, 0, 4), Catch::Contains("must lie in"));
    Triangles island(1, 3);
    island << 0, 1, 2;
    REQUIRE(shortestPath(buildEdgeGraph(V, island, 4), 0, 3).empty());
    REQUIRE_THROWS_WITH(buildEdgeGraph(V, F, 6), Catch::Contains("vertex limit 6"));
}

// Tests of geometry/wedges: the vertex-to-triangle incidence and the one-rings, on a
// tetrahedron by hand and on larger meshes against their definitions.
#include "geometry/wedges.h"

#include "geometry/primitives.h"

#include <array>
#include <catch2/catch.hpp>
#include <set>
#include <vector>

using namespace facesketch;

namespace {
// A tetrahedron's four triangles: every vertex touches three of them and every other vertex.
Triangles tetrahedron()
{
    Triangles F(4, 3);
    F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
    return F;
}
} // namespace

TEST_CASE("wedges: a tetrahedron's wedges and one-rings, by hand")
{
    const Wedges w = buildWedges(tetrahedron(), 4);
    REQUIRE(w.offsets == std::vector<std::uint32_t> { 0, 3, 6, 9, 12 });
    // Each triangle (a, b, c) at vertex a gives (b, c), in the order of the triangles in F.
    using Pair = std::array<std::uint32_t, 2>;
    const std::vector<Pair> expected = {
        { 2, 1 }, { 1, 3 }, { 3, 2 }, // vertex 0: triangles 0, 1, 2
        { 0, 2 }, { 3, 0 }, { 2, 3 }, // vertex 1: triangles 0, 1, 3
        { 1, 0 }, { 0, 3 }, { 3, 1 }, // vertex 2: triangles 0, 2, 3
        { 0, 1 }, { 2, 0 }, { 1, 2 }, // vertex 3: triangles 1, 2, 3
    };
    REQUIRE(w.corners == expected);
    const Neighbours n = buildNeighbours(w);
    REQUIRE(n.offsets == std::vector<std::uint32_t> { 0, 3, 6, 9, 12 });
    REQUIRE(n.vertices == std::vector<std::uint32_t> { 1, 2, 3, 0, 2, 3, 0, 1, 3, 0, 1, 2 });
}

TEST_CASE("wedges: a vertex in no triangle has no wedges and an empty one-ring")
{
    const Triangles F = tetrahedron();
    const Wedges w = buildWedges(F, 6); // vertices 4 and 5 unused
    REQUIRE(w.offsets.size() == 7);
    REQUIRE(w.offsets[4] == 12);
    REQUIRE(w.offsets[5] == 12);
    REQUIRE(w.offsets[6] == 12);
    const Neighbours n = buildNeighbours(w);
    REQUIRE(n.offsets.size() == 7);
    REQUIRE(n.offsets[4] == n.offsets[5]);
    REQUIRE(n.offsets[5] == n.offsets[6]);
    REQUIRE(n.vertices.size() == 12);
}

TEST_CASE("wedges: every triangle corner appears once, in winding order")
{
    const Mesh s = makeIcosphere(1.0, 1);
    const Wedges w = buildWedges(s.F, s.V.rows());
    REQUIRE(w.offsets.back() == 3 * s.F.rows());
    REQUIRE(w.corners.size() == static_cast<size_t>(3 * s.F.rows()));
    for (Eigen::Index v = 0; v < s.V.rows(); ++v)
        for (std::uint32_t k = w.offsets[v]; k < w.offsets[v + 1]; ++k) {
            const auto [b, c] = w.corners[k];
            bool found = false;
            for (Eigen::Index t = 0; t < s.F.rows(); ++t)
                for (int r = 0; r < 3; ++r)
                    found |= s.F(t, r) == v && s.F(t, (r + 1) % 3) == Eigen::Index(b) && s.F(t, (r + 2) % 3) == Eigen::Index(c);
            REQUIRE(found);
        }
}

TEST_CASE("wedges: one-rings hold each edge neighbour once, ascending, on both ends of every edge")
{
    const Mesh s = makeGrid(4, 3, 3.0, 2.0); // boundary vertices have open rings
    const Neighbours n = buildNeighbours(buildWedges(s.F, s.V.rows()));
    REQUIRE(n.offsets.size() == static_cast<size_t>(s.V.rows()) + 1);
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (Eigen::Index t = 0; t < s.F.rows(); ++t)
        for (int r = 0; r < 3; ++r) {
            const auto a = static_cast<std::uint32_t>(s.F(t, r)), b = static_cast<std::uint32_t>(s.F(t, (r + 1) % 3));
            edges.insert({ a, b });
            edges.insert({ b, a });
        }
    std::set<std::pair<std::uint32_t, std::uint32_t>> listed;
    for (std::uint32_t v = 0; v + 1 < n.offsets.size(); ++v)
        for (std::uint32_t k = n.offsets[v]; k < n.offsets[v + 1]; ++k) {
            if (k > n.offsets[v])
                REQUIRE(n.vertices[k - 1] < n.vertices[k]);
            listed.insert({ v, n.vertices[k] });
        }
    REQUIRE(listed == edges);
    REQUIRE(n.vertices.size() == edges.size());
}

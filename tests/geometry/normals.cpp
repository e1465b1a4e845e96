#include "geometry/normals.h"
#include "geometry/primitives.h"
#include "geometry/wedges.h"

#include <catch2/catch.hpp>
#include <set>

using namespace facesketch;

TEST_CASE("normals: icosphere normals point radially outward")
{
    const Mesh s = makeIcosphere(2.0, 3);
    const Vertices N = vertexNormals(s);
    for (Eigen::Index v = 0; v < s.V.rows(); ++v) {
        const Eigen::RowVector3d radial = s.V.row(v).normalized();
        INFO("vertex " << v);
        REQUIRE(N.row(v).norm() == Approx(1.0).epsilon(1e-12));
        REQUIRE(N.row(v).dot(radial) > 0.999);
    }
}

TEST_CASE("normals: area weighting, checked by hand on a fan")
{
    // Vertex 0 shared by a big triangle in the xy plane and a small one in the xz plane:
    // cross products (0,0,4) and (0,-1,0) sum to (0,-1,4).
    Mesh m;
    m.V.resize(5, 3);
    m.V << 0, 0, 0, 2, 0, 0, 0, 2, 0, 1, 0, 0, 0, 0, 1;
    m.F.resize(2, 3);
    m.F << 0, 1, 2, 0, 3, 4;
    const Vertices N = vertexNormals(m);
    const Eigen::RowVector3d expected = Eigen::RowVector3d(0, -1, 4).normalized();
    REQUIRE((N.row(0) - expected).norm() < 1e-12);
    REQUIRE((N.row(1) - Eigen::RowVector3d(0, 0, 1)).norm() < 1e-12);
}

TEST_CASE("normals: a vertex without area gets the zero vector")
{
    Mesh m;
    m.V.resize(4, 3);
    m.V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 5, 5, 5; // collinear triangle, isolated vertex 3
    m.F.resize(1, 3);
    m.F << 0, 1, 2;
    const Vertices N = vertexNormals(m);
    REQUIRE(N.row(0).norm() == 0.0);
    REQUIRE(N.row(3).norm() == 0.0);
}

TEST_CASE("normals: the batch reference equals the per-mesh function")
{
    const Mesh s = makeIcosphere(1.0, 2);
    std::vector<float> positions;
    for (int m = 0; m < 3; ++m)
        for (Eigen::Index v = 0; v < s.V.rows(); ++v)
            for (int c = 0; c < 3; ++c)
                positions.push_back(static_cast<float>(s.V(v, c) * (1.0 + 0.3 * m * (c == 1))));
    const std::vector<float> batch = vertexNormalsBatch(positions, s.F, s.V.rows());
    for (int m = 0; m < 3; ++m) {
        Mesh scaled = s;
        for (Eigen::Index v = 0; v < s.V.rows(); ++v)
            for (int c = 0; c < 3; ++c)
                scaled.V(v, c) = positions[(m * s.V.rows() + v) * 3 + c];
        const Vertices N = vertexNormals(scaled);
        for (Eigen::Index v = 0; v < s.V.rows(); ++v)
            for (int c = 0; c < 3; ++c)
                REQUIRE(batch[(m * s.V.rows() + v) * 3 + c] == Approx(N(v, c)).margin(1e-6));
    }
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

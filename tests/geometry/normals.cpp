#include "geometry/normals.h"
#include "geometry/primitives.h"

#include <catch2/catch.hpp>

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

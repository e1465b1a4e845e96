// Tests of geometry/primitives: vertex and triangle counts, where the vertices lie, closed or
// open as documented, and triangles wound counter-clockwise seen from outside.
#include "geometry/primitives.h"

#include "core/error.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

using namespace facesketch;

namespace {

// Directed edge counts. A closed, consistently wound surface has every directed edge once and
// its reverse once; an open one has boundary edges whose reverse is missing.
struct EdgeCheck {
    bool consistent = true;   ///< no directed edge twice
    std::size_t edges = 0;    ///< undirected
    std::size_t boundary = 0; ///< undirected edges in one triangle only
};

EdgeCheck checkEdges(const Mesh& m)
{
    std::map<std::pair<int, int>, int> directed;
    for (Eigen::Index t = 0; t < m.F.rows(); ++t)
        for (int c = 0; c < 3; ++c)
            ++directed[{ m.F(t, c), m.F(t, (c + 1) % 3) }];
    EdgeCheck e;
    for (const auto& [edge, count] : directed) {
        e.consistent = e.consistent && count == 1;
        const bool reverse = directed.count({ edge.second, edge.first }) > 0;
        if (!reverse)
            ++e.boundary, ++e.edges;
        else if (edge.first < edge.second)
            ++e.edges;
    }
    return e;
}

// The unnormalised normal and centroid of triangle t.
Eigen::RowVector3d faceNormal(const Mesh& m, Eigen::Index t)
{
    const Eigen::RowVector3d a = m.V.row(m.F(t, 0)), b = m.V.row(m.F(t, 1)), c = m.V.row(m.F(t, 2));
    return (b - a).cross(c - a);
}

Eigen::RowVector3d centroid(const Mesh& m, Eigen::Index t)
{
    return (m.V.row(m.F(t, 0)) + m.V.row(m.F(t, 1)) + m.V.row(m.F(t, 2))) / 3.0;
}

} // namespace

TEST_CASE("primitives: icospheres have 10 * 4^s + 2 vertices on the sphere, closed, normals outward")
{
    for (int s = 0; s <= 3; ++s) {
        const Mesh m = makeIcosphere(2.5, s);
        const Eigen::Index expected = 10 * (Eigen::Index(1) << (2 * s)) + 2;
        INFO("subdivisions " << s);
        REQUIRE(m.V.rows() == expected);
        REQUIRE(m.F.rows() == 20 * (Eigen::Index(1) << (2 * s)));
        for (Eigen::Index v = 0; v < m.V.rows(); ++v)
            REQUIRE(m.V.row(v).norm() == Approx(2.5).epsilon(1e-12));
        const EdgeCheck e = checkEdges(m);
        REQUIRE(e.consistent);
        REQUIRE(e.boundary == 0);
        REQUIRE(m.V.rows() - Eigen::Index(e.edges) + m.F.rows() == 2); // Euler: a sphere
        for (Eigen::Index t = 0; t < m.F.rows(); ++t)
            REQUIRE(faceNormal(m, t).dot(centroid(m, t)) > 0);
    }
    REQUIRE_THROWS_WITH(makeIcosphere(0.0, 1), Catch::Contains("makeIcosphere"));
    REQUIRE_THROWS_WITH(makeIcosphere(1.0, 9), Catch::Contains("subdivisions 9"));
}

TEST_CASE("primitives: a torus has rings x tube vertices at the documented angles, closed, genus one, normals outward")
{
    const double R = 30, r = 8;
    const int rings = 24, tube = 12;
    const Mesh m = makeTorus(R, r, rings, tube);
    REQUIRE(m.V.rows() == rings * tube);
    REQUIRE(m.F.rows() == 2 * rings * tube);
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < tube; ++j) {
            const double u = 2 * M_PI * i / rings, v = 2 * M_PI * j / tube;
            const Eigen::RowVector3d expected((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
            REQUIRE((m.V.row(i * tube + j) - expected).norm() < 1e-12);
        }
    const EdgeCheck e = checkEdges(m);
    REQUIRE(e.consistent);
    REQUIRE(e.boundary == 0);
    REQUIRE(m.V.rows() - Eigen::Index(e.edges) + m.F.rows() == 0); // Euler: a torus
    for (Eigen::Index t = 0; t < m.F.rows(); ++t) {
        const Eigen::RowVector3d c = centroid(m, t);
        const Eigen::RowVector3d tubeCentre = R * Eigen::RowVector3d(c.x(), c.y(), 0).normalized();
        REQUIRE(faceNormal(m, t).dot(c - tubeCentre) > 0);
    }
    REQUIRE_THROWS_WITH(makeTorus(5, 8, 24, 12), Catch::Contains("0 < r < R"));
}

TEST_CASE("primitives: an open cylinder has two boundary loops, vertices on the radius, normals outward")
{
    const double radius = 4, length = 10;
    const int segments = 16, rings = 5;
    const Mesh m = makeCylinder(radius, length, segments, rings);
    REQUIRE(m.V.rows() == segments * (rings + 1));
    REQUIRE(m.F.rows() == 2 * segments * rings);
    for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
        REQUIRE(std::hypot(m.V(v, 0), m.V(v, 1)) == Approx(radius).epsilon(1e-12));
        REQUIRE(m.V(v, 2) >= 0);
        REQUIRE(m.V(v, 2) <= length);
    }
    const EdgeCheck e = checkEdges(m);
    REQUIRE(e.consistent);
    REQUIRE(e.boundary == 2 * segments); // the rims at z = 0 and z = length
    for (Eigen::Index t = 0; t < m.F.rows(); ++t) {
        const Eigen::RowVector3d c = centroid(m, t);
        REQUIRE(faceNormal(m, t).dot(Eigen::RowVector3d(c.x(), c.y(), 0)) > 0);
    }
    REQUIRE_THROWS_WITH(makeCylinder(4, 10, 2, 5), Catch::Contains("makeCylinder"));
}

TEST_CASE("primitives: a grid has vertex (i, j) at row j * nx + i, spans its size, and faces +z")
{
    const int nx = 5, ny = 4;
    const Mesh m = makeGrid(nx, ny, 8.0, 3.0);
    REQUIRE(m.V.rows() == nx * ny);
    REQUIRE(m.F.rows() == 2 * (nx - 1) * (ny - 1));
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            REQUIRE(m.V(j * nx + i, 0) == Approx(8.0 * (double(i) / (nx - 1) - 0.5)));
            REQUIRE(m.V(j * nx + i, 1) == Approx(3.0 * (double(j) / (ny - 1) - 0.5)));
            REQUIRE(m.V(j * nx + i, 2) == 0.0);
        }
    const EdgeCheck e = checkEdges(m);
    REQUIRE(e.consistent);
    REQUIRE(e.boundary == std::size_t(2 * (nx - 1) + 2 * (ny - 1)));
    double area = 0;
    for (Eigen::Index t = 0; t < m.F.rows(); ++t) {
        const Eigen::RowVector3d n = faceNormal(m, t);
        REQUIRE(n.z() > 0);
        area += n.norm() / 2;
    }
    REQUIRE(area == Approx(8.0 * 3.0));
    REQUIRE_THROWS_WITH(makeGrid(1, 4, 8.0, 3.0), Catch::Contains("makeGrid"));
}

// Tests of registration/surface_query: closest points against brute force, and the boundary flag.
#include "registration/surface_query.h"

#include "core/error.h"
#include "geometry/primitives.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using namespace facesketch;
using namespace facesketch::registration;

TEST_CASE("closestPointOnTriangle: inside, on an edge and at a corner")
{
    const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
    Eigen::Vector3d bary;
    REQUIRE((closestPointOnTriangle({ 0.5, 0.5, 3.0 }, a, b, c, bary) - Eigen::Vector3d(0.5, 0.5, 0)).norm() < 1e-12);
    REQUIRE((bary - Eigen::Vector3d(0.5, 0.25, 0.25)).norm() < 1e-12);
    REQUIRE((closestPointOnTriangle({ 1.0, -1.0, 0.0 }, a, b, c, bary) - Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);
    REQUIRE(bary(2) == 0.0);
    REQUIRE((closestPointOnTriangle({ 3.0, 3.0, 0.0 }, a, b, c, bary) - Eigen::Vector3d(1, 1, 0)).norm() < 1e-12);
    REQUIRE((closestPointOnTriangle({ -1.0, -1.0, 1.0 }, a, b, c, bary) - a).norm() < 1e-12);
    REQUIRE(bary(0) == 1.0);
}

TEST_CASE("SurfaceQuery: equals brute force on an icosphere, for points inside, near and far")
{
    const Mesh sphere = makeIcosphere(30.0, 3);
    const SurfaceQuery query(sphere);
    for (int i = 0; i < 60; ++i) {
        const double r = 5.0 + 1.5 * i; // from deep inside to far outside
        const Eigen::Vector3d p = r * Eigen::Vector3d(std::sin(1.3 * i), std::cos(0.7 * i), std::sin(2.1 * i + 0.4)).normalized();
        double brute = std::numeric_limits<double>::infinity();
        for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
            Eigen::Vector3d bary;
            const Eigen::Vector3d q = closestPointOnTriangle(p, sphere.V.row(sphere.F(f, 0)).transpose(),
                sphere.V.row(sphere.F(f, 1)).transpose(), sphere.V.row(sphere.F(f, 2)).transpose(), bary);
            brute = std::min(brute, (q - p).norm());
        }
        const ClosestPoint c = query.closest(p);
        INFO("point " << i << " at radius " << r);
        REQUIRE(std::abs(c.distance - brute) < 1e-9);
        REQUIRE(std::abs((c.point - p).norm() - c.distance) < 1e-9);
        // The barycentric coordinates rebuild the point from the triangle's corners.
        Eigen::Vector3d fromCorners = Eigen::Vector3d::Zero();
        for (int k = 0; k < 3; ++k)
            fromCorners += c.barycentric(k) * sphere.V.row(sphere.F(c.triangle, k)).transpose();
        REQUIRE(std::abs(c.barycentric.sum() - 1.0) < 1e-12);
        REQUIRE((fromCorners - c.point).norm() < 1e-9);
        REQUIRE_FALSE(c.onBoundary); // a closed surface has no boundary
    }
}

TEST_CASE("SurfaceQuery: a point over a patch is on it, a point beside the patch is on its boundary")
{
    const Mesh grid = makeGrid(11, 11, 20.0, 20.0);
    const SurfaceQuery query(grid);
    const ClosestPoint over = query.closest({ 3.3, -2.1, 4.0 });
    REQUIRE(over.distance == Approx(4.0).epsilon(1e-12));
    REQUIRE_FALSE(over.onBoundary);
    const ClosestPoint beside = query.closest({ 14.0, 2.0, 1.0 });
    REQUIRE(beside.distance == Approx(std::hypot(4.0, 1.0)).epsilon(1e-12));
    REQUIRE(beside.onBoundary);
}

TEST_CASE("SurfaceQuery: a mesh without triangles is refused")
{
    Mesh empty;
    REQUIRE_THROWS_AS(SurfaceQuery(empty), Error);
}

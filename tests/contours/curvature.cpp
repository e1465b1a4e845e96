#include "contours/curvature.h"
#include "geometry/primitives.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;

// Tolerances are the estimator's discretisation error at these resolutions, measured once and
// stated here: they shrink with finer meshes, they are not fitted to pass.

TEST_CASE("curvature: sphere of radius 2 has k1 = k2 = 1/2 everywhere, convex positive")
{
    const Mesh sphere = makeIcosphere(2.0, 4);
    const Curvature c = estimateCurvature(sphere);
    for (Eigen::Index v = 0; v < sphere.V.rows(); ++v) {
        INFO("vertex " << v);
        REQUIRE(c.k1[v] == Approx(0.5).epsilon(0.01));
        REQUIRE(c.k2[v] == Approx(0.5).epsilon(0.01));
        REQUIRE(c.k1[v] >= c.k2[v]);
        REQUIRE(std::abs(c.dir1.row(v).dot(c.normal.row(v))) < 1e-9);
        REQUIRE((c.dir1.row(v).cross(c.dir2.row(v)) - c.normal.row(v)).norm() < 1e-9);
    }
    REQUIRE(c.area.sum() == Approx(4 * M_PI * 4).epsilon(0.01));
    // The derivative of a constant curvature vanishes.
    REQUIRE(c.dcurv.cwiseAbs().maxCoeff() < 0.01 * 0.5 * 0.5);
}

TEST_CASE("curvature: cylinder of radius 5 has k1 = 1/5 around, k2 = 0 along the axis")
{
    const Mesh cyl = makeCylinder(5.0, 20.0, 96, 24);
    const Curvature c = estimateCurvature(cyl);
    for (Eigen::Index v = 0; v < cyl.V.rows(); ++v) {
        if (cyl.V(v, 2) < 1e-9 || cyl.V(v, 2) > 20 - 1e-9)
            continue; // boundary rings: one-sided estimates
        INFO("vertex " << v);
        REQUIRE(c.k1[v] == Approx(0.2).epsilon(0.01));
        REQUIRE(std::abs(c.k2[v]) < 0.002);
        REQUIRE(std::abs(c.dir1(v, 2)) < 0.01); // the bending direction is around the axis
    }
}

TEST_CASE("curvature: torus matches the closed form, and so does the curvature derivative")
{
    const double R = 3.0, r = 1.0;
    const int ring = 192, tube = 96;
    const Mesh torus = makeTorus(R, r, ring, tube);
    const Curvature c = estimateCurvature(torus);
    double worstK = 0, worstC = 0, maxC = 0;
    for (Eigen::Index vi = 0; vi < torus.V.rows(); ++vi) {
        const double v = 2 * M_PI * (vi % tube) / tube, u = 2 * M_PI * (vi / tube) / ring;
        const double kTube = 1 / r, kRing = std::cos(v) / (R + r * std::cos(v));
        worstK = std::max({ worstK, std::abs(c.k1[vi] - kTube), std::abs(c.k2[vi] - kRing) });

        // C(x, x, x) for a tangent x is frame independent: 3 x_v x_u^2 dk_ring/ds with e_v
        // along increasing v (surface of revolution: meridians are geodesics, so the only
        // non-zero component is C(e_v, e_u, e_u) = d k_ring / d s).
        const Eigen::RowVector3d eu(-std::sin(u), std::cos(u), 0);
        const Eigen::RowVector3d ev(-std::sin(v) * std::cos(u), -std::sin(v) * std::sin(u), std::cos(v));
        const double dkRing = -R * std::sin(v) / (r * std::pow(R + r * std::cos(v), 2));
        maxC = std::max(maxC, std::abs(dkRing));
        for (double angle : { 0.3, 1.1, 2.0 }) {
            const Eigen::RowVector3d x = std::cos(angle) * eu + std::sin(angle) * ev;
            const double expected = 3 * x.dot(ev) * std::pow(x.dot(eu), 2) * dkRing;
            const double a = x.dot(c.dir1.row(vi)), b = x.dot(c.dir2.row(vi));
            const auto d = c.dcurv.row(vi);
            const double got = d[0] * a * a * a + 3 * d[1] * a * a * b + 3 * d[2] * a * b * b + d[3] * b * b * b;
            worstC = std::max(worstC, std::abs(got - expected));
        }
    }
    INFO("worst curvature error " << worstK << " (1/r = 1), worst C(x,x,x) error " << worstC << " of max |dk/ds| " << maxC);
    REQUIRE(worstK < 0.002);
    REQUIRE(worstC < 0.01 * 3 * maxC);
}

TEST_CASE("curvature: radial curvature on a sphere is 1/r from every view, and D_w k_r = 2 K cot(theta)")
{
    const Mesh sphere = makeIcosphere(1.0, 4);
    const Curvature c = estimateCurvature(sphere);
    const Eigen::Vector3d toCamera = Eigen::Vector3d(0.2, 0.3, 1).normalized();
    for (Eigen::Index v = 0; v < sphere.V.rows(); v += 37) {
        const RadialCurvature rc = radialCurvature(c, v, toCamera);
        if (std::abs(rc.ndotv) > 0.99)
            continue;
        INFO("vertex " << v);
        REQUIRE(rc.kr == Approx(1.0).epsilon(0.01));
        const double cot = rc.ndotv / std::sqrt(1 - rc.ndotv * rc.ndotv);
        REQUIRE(rc.dwkr == Approx(2 * cot).margin(0.02 + 0.02 * std::abs(cot)));
    }
}

TEST_CASE("curvature: rtsc's numerator differs from sin(theta) D_w k_r by -2 cos(theta) k_r k_t, so both agree where k_r = 0")
{
    // One vertex with a saddle (k1 > 0 > k2) and a derivative tensor, seen from several views:
    // K + tau_r^2 = k_r k_t (k_t the normal curvature across w), so the two forms of the
    // derivative differ by 2 cot(theta) k_r k_t, which vanishes on the suggestive contour.
    Curvature c;
    c.normal = Vertices(1, 3);
    c.normal << 0, 0, 1;
    c.dir1 = Vertices(1, 3);
    c.dir1 << 1, 0, 0;
    c.dir2 = Vertices(1, 3);
    c.dir2 << 0, 1, 0;
    c.k1 = Eigen::VectorXd::Constant(1, 0.3);
    c.k2 = Eigen::VectorXd::Constant(1, -0.12);
    c.dcurv.resize(1, 4);
    c.dcurv << 0.05, -0.02, 0.01, 0.04;
    c.area = Eigen::VectorXd::Ones(1);
    for (const double phi : { 0.2, 0.9, 1.4, 2.5 })
        for (const double theta : { 0.3, 0.8, 1.3 }) {
            const Eigen::Vector3d toCamera(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            const RadialCurvature r = radialCurvature(c, 0, toCamera);
            const double kt = c.k1[0] * std::sin(phi) * std::sin(phi) + c.k2[0] * std::cos(phi) * std::cos(phi);
            INFO("phi " << phi << ", theta " << theta);
            REQUIRE(r.rtscNumerator - std::sin(theta) * r.dwkr == Approx(-2 * std::cos(theta) * r.kr * kt).margin(1e-12));
        }
    // On the zero set of k_r (tan^2 phi = -k1 / k2) the two are one.
    const double phi = std::atan(std::sqrt(-c.k1[0] / c.k2[0])), theta = 0.7;
    const RadialCurvature r
        = radialCurvature(c, 0, Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
    REQUIRE(std::abs(r.kr) < 1e-12);
    REQUIRE(r.rtscNumerator == Approx(std::sin(theta) * r.dwkr).epsilon(1e-12));
}

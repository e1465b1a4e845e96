// Tests of registration/rbf: the RBF of thesis eqs. 3.1-3.3 interpolates its feature points,
// reproduces affine maps exactly, and refuses degenerate point sets.
#include "registration/rbf.h"

#include "core/error.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;
using namespace facesketch::registration;

namespace {

// n points spread over about 100 mm, not on one plane; deterministic.
Vertices spread(int n, double phase = 0.0)
{
    Vertices P(n, 3);
    for (int i = 0; i < n; ++i)
        P.row(i) << 50.0 * std::sin(0.9 * i + 0.3 + phase), 60.0 * std::cos(1.7 * i + phase), 40.0 * std::sin(2.3 * i + 1.0);
    return P;
}

} // namespace

TEST_CASE("rbf: interpolates its feature points exactly")
{
    const Vertices P = spread(20);
    Vertices Q = P;
    for (Eigen::Index i = 0; i < Q.rows(); ++i)
        Q.row(i) += Eigen::RowVector3d(3.0 * std::sin(5.0 * i), 2.0 * std::cos(3.0 * i), 4.0 * std::sin(7.0 * i + 1.0));
    const RbfWarp f(P, Q);
    const Vertices image = f.apply(P);
    REQUIRE((image - Q).cwiseAbs().maxCoeff() < 1e-8);
    // The warp is not just affine here: the RBF weights carry the non-affine part.
    REQUIRE(f.weights().cwiseAbs().maxCoeff() > 1.0);
}

TEST_CASE("rbf: reproduces an affine map exactly, away from the feature points too")
{
    const Vertices P = spread(15);
    Eigen::Matrix3d M = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix() * 1.15;
    M(0, 1) += 0.1; // a shear
    const Eigen::RowVector3d t(12.0, -30.0, 7.5);
    const Vertices Q = (P * M.transpose()).rowwise() + t;
    const RbfWarp f(P, Q);
    REQUIRE((f.linear() - M).cwiseAbs().maxCoeff() < 1e-9);
    REQUIRE((f.translation() - t.transpose()).cwiseAbs().maxCoeff() < 1e-7);
    REQUIRE(f.weights().cwiseAbs().maxCoeff() < 1e-6);
    const Vertices other = spread(40, 0.77) * 1.3;
    const Vertices expected = (other * M.transpose()).rowwise() + t;
    REQUIRE((f.apply(other) - expected).cwiseAbs().maxCoeff() < 1e-8);
}

TEST_CASE("rbf: stiffness is the distance to the nearest other point")
{
    Vertices P(4, 3);
    P << 0, 0, 0, 10, 0, 0, 0, 20, 0, 0, 0, 5;
    const RbfWarp f(P, P);
    REQUIRE(f.stiffness()(0) == Approx(5.0));
    REQUIRE(f.stiffness()(1) == Approx(10.0));
    REQUIRE(f.stiffness()(2) == Approx(20.0));
    REQUIRE(f.stiffness()(3) == Approx(5.0));
}

TEST_CASE("rbf: refuses too few, coincident and coplanar points")
{
    const Vertices P = spread(3);
    REQUIRE_THROWS_WITH(RbfWarp(P, P), Catch::Contains("3 feature points"));
    Vertices twice = spread(6);
    twice.row(4) = twice.row(1);
    REQUIRE_THROWS_WITH(RbfWarp(twice, twice), Catch::Contains("coincide"));
    Vertices flat = spread(8);
    flat.col(2).setConstant(4.0);
    REQUIRE_THROWS_WITH(RbfWarp(flat, flat), Catch::Contains("one plane"));
    REQUIRE_THROWS_WITH(RbfWarp(spread(6), spread(5)), Catch::Contains("6 template points but 5"));
}

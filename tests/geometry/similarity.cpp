// Tests of geometry/similarity: the Umeyama fit against known transforms, the reflection
// guard and the degenerate cases.
#include "geometry/similarity.h"

#include "core/error.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;

namespace {

// n points spread over a box of about 40 mm, not on one plane: deterministic, so the tests
// need no random generator.
Vertices spreadPoints(int n)
{
    Vertices P(n, 3);
    for (int i = 0; i < n; ++i)
        P.row(i) << 20.0 * std::sin(0.9 * i + 0.3), 15.0 * std::cos(1.7 * i), 10.0 * std::sin(2.3 * i + 1.0);
    return P;
}

Similarity knownSimilarity()
{
    Similarity s;
    s.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
    s.scale = 1.3;
    s.translation = { 4.0, -7.0, 2.5 };
    return s;
}

} // namespace

TEST_CASE("similarity: apply moves one point and every row alike")
{
    const Similarity s = knownSimilarity();
    const Vertices P = spreadPoints(5);
    const Vertices moved = s.apply(P);
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
        const Eigen::Vector3d expected = 1.3 * s.rotation * P.row(i).transpose() + Eigen::Vector3d(4.0, -7.0, 2.5);
        CHECK((moved.row(i).transpose() - expected).norm() < 1e-12);
        CHECK((s.apply(Eigen::Vector3d(P.row(i).transpose())) - expected).norm() < 1e-12);
    }
}

TEST_CASE("similarity: the fit recovers an exact similarity and an exact rigid motion")
{
    const Vertices from = spreadPoints(12);
    Similarity truth = knownSimilarity();
    Similarity fit = fitSimilarity(from, truth.apply(from));
    CHECK((fit.rotation - truth.rotation).norm() < 1e-12);
    CHECK(std::abs(fit.scale - truth.scale) < 1e-12);
    CHECK((fit.translation - truth.translation).norm() < 1e-10);

    truth.scale = 1.0;
    fit = fitSimilarity(from, truth.apply(from), false);
    CHECK(fit.scale == 1.0);
    CHECK((fit.apply(from) - truth.apply(from)).norm() < 1e-10);
}

TEST_CASE("similarity: without scale, a scaled copy gives the best rotation at scale 1")
{
    const Vertices from = spreadPoints(10);
    const Similarity truth = knownSimilarity();
    const Similarity fit = fitSimilarity(from, truth.apply(from), false);
    CHECK(fit.scale == 1.0);
    CHECK((fit.rotation - truth.rotation).norm() < 1e-12);
    // The centroids still meet.
    CHECK((fit.apply(from).colwise().mean() - truth.apply(from).colwise().mean()).norm() < 1e-10);
}

TEST_CASE("similarity: mirrored points give a proper rotation, not a reflection")
{
    const Vertices from = spreadPoints(10);
    Vertices to = from;
    to.col(0) *= -1.0;
    const Similarity fit = fitSimilarity(from, to);
    CHECK(std::abs(fit.rotation.determinant() - 1.0) < 1e-12);
    CHECK((fit.rotation * fit.rotation.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-12);
}

TEST_CASE("similarity: too few or collinear points give the translation of the centroids")
{
    Vertices from(2, 3), to(2, 3);
    from << 0, 0, 0, 1, 0, 0;
    to << 5, 1, 0, 5, 2, 0;
    Similarity fit = fitSimilarity(from, to);
    CHECK(fit.rotation == Eigen::Matrix3d::Identity());
    CHECK(fit.scale == 1.0);
    CHECK((fit.translation - Eigen::Vector3d(4.5, 1.5, 0)).norm() < 1e-12);

    Vertices line(4, 3), moved(4, 3);
    for (int i = 0; i < 4; ++i) {
        line.row(i) << i, 0, 0;
        moved.row(i) << 0, i, 1;
    }
    fit = fitSimilarity(line, moved);
    CHECK(fit.rotation == Eigen::Matrix3d::Identity());
    CHECK((fit.translation - Eigen::Vector3d(-1.5, 1.5, 1)).norm() < 1e-12);
    REQUIRE_THROWS_WITH(fitSimilarity(line, from), Catch::Contains("4 and 2 points"));
    REQUIRE_THROWS_AS(fitSimilarity(Vertices(0, 3), Vertices(0, 3)), Error);
}

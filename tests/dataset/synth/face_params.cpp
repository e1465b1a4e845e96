// Population model of the synthetic faces: determinism, norms table (the portable generator
// itself is tested in tests/core/random.cpp).
#include "dataset/synth/face_params.h"
#include "test_common.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

using namespace facesketch;
using namespace facesketch::dataset;

TEST_CASE("face_params: identities depend only on (seed, index) and vary")
{
    const FaceParams a = sampleFaceParams(3, 17), b = sampleFaceParams(3, 17), c = sampleFaceParams(3, 18), d = sampleFaceParams(4, 17);
    REQUIRE(a.exex == b.exex);
    REQUIRE(a.detail.size() == b.detail.size());
    REQUIRE(a.detail.back().height == b.detail.back().height);
    REQUIRE(a.exex != c.exex);
    REQUIRE(a.exex != d.exex);
    int women = 0;
    double minAge = 100, maxAge = 0;
    for (int i = 0; i < 400; ++i) {
        const FaceParams p = sampleFaceParams(1, i);
        women += p.female;
        minAge = std::min(minAge, p.age);
        maxAge = std::max(maxAge, p.age);
        REQUIRE(p.upperVermilion > 2);
        REQUIRE(p.nostrilSize > 1);
    }
    REQUIRE(women > 150);
    REQUIRE(women < 250);
    REQUIRE(minAge >= 20);
    REQUIRE(maxAge <= 65);
}

TEST_CASE("face_params: sampled Farkas measures keep the norms' means and SDs")
{
    // The measures themselves (before geometry; face_shape.cpp checks the meshes).
    const auto& norms = farkasNorms();
    REQUIRE(norms.size() == 7);
    double sum = 0, sum2 = 0;
    int n = 0;
    for (int i = 0; i < 4000; ++i) {
        const FaceParams p = sampleFaceParams(9, i);
        if (p.female)
            continue;
        sum += p.exex;
        sum2 += p.exex * p.exex;
        ++n;
    }
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    REQUIRE(mean == Approx(norms[0].meanMale).epsilon(0.01));
    REQUIRE(sd == Approx(norms[0].sdMale).epsilon(0.1));
}

TEST_CASE("face_params: shape fields are mirror-symmetric or antisymmetric and the fast sum equals the fields' sum")
{
    for (double width : { kMeanFieldWidth, kFieldWidth })
        for (int k = 0; k < kShapeFields; ++k) {
            INFO("field " << k << ", width " << width);
            const double sign = k < 28 ? 1.0 : -1.0;
            for (double theta : { 0.0, 0.13, 0.3, 0.71 })
                for (double phi : { 0.5, 0.02, -0.4, -0.93 })
                    REQUIRE(shapeField(k, -theta, phi, width) == Approx(sign * shapeField(k, theta, phi, width)).margin(1e-15));
        }
    // Each bump peaks at 1 at its centre: field 0 at (0, 0.55), field 28 (antisymmetric, row 0,
    // column 1) at +-0.3, less its mirror image's tail.
    REQUIRE(shapeField(0, 0, 0.55, 0.2) == Approx(1.0).epsilon(1e-12));
    REQUIRE(shapeField(28, 0.3, 0.55, 0.2) == Approx(1 - std::exp(-0.36 / 0.04)).epsilon(1e-12));
    REQUIRE(shapeField(28, 0.3, 0.55, 0.28) == Approx(1 - std::exp(-0.36 / 0.0784)).epsilon(1e-12));

    // The fast sums: a face's own coefficients on the wider bumps, the population's means on
    // the narrower ones.
    const FaceParams p = sampleFaceParams(1, 5);
    REQUIRE(p.shapeModes.size() == static_cast<size_t>(kShapeFields));
    for (double theta : { -0.8, -0.2, 0.0, 0.45 })
        for (double phi : { 0.6, 0.1, -0.55, -1.0 }) {
            double sum = 0;
            for (int k = 0; k < kShapeFields; ++k)
                sum += p.shapeModes[static_cast<size_t>(k)] * shapeField(k, theta, phi, kFieldWidth);
            double meanSum = 0;
            for (int k = 0; k < kShapeFields; ++k)
                meanSum += shapeFieldMeans()[static_cast<size_t>(k)] * shapeField(k, theta, phi, kMeanFieldWidth);
            const auto [own, means] = shapeFieldSums(p.shapeModes, shapeFieldMeans(), theta, phi);
            REQUIRE(own == Approx(sum).margin(1e-12));
            REQUIRE(means == Approx(meanSum).margin(1e-12));
        }
    // The population means: the 28 symmetric fields' are fitted (some non-zero), the 21
    // antisymmetric ones' are 0, so the mean face stays symmetric.
    REQUIRE(shapeFieldMeans().size() == static_cast<size_t>(kShapeFields));
    REQUIRE(std::count(shapeFieldMeans().begin(), shapeFieldMeans().begin() + 28, 0.0) < 28);
    REQUIRE(std::count(shapeFieldMeans().begin() + 28, shapeFieldMeans().end(), 0.0) == 21);
}

TEST_CASE("face_params: symmetric shape field coefficients are correlated along a lattice row, and across rows by the face-wide factors")
{
    // Fields of one row share its factor (weight 0.5: correlation 0.25). Every symmetric field
    // also shares the face's factors through its own random direction of loadings (weight 0.7),
    // which adds 0.75 x 0.49 x (l_a . l_b) to a pair: on average over many pairs about 0, in
    // absolute value about 0.12. Independent coefficients would give |r| about 0.013 from 4,000
    // faces.
    const int n = 4000, fields = 28;
    Eigen::MatrixXd c(n, fields);
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < fields; ++k)
            c(i, k) = sampleFaceParams(2, i).shapeModes[static_cast<size_t>(k)];
    const Eigen::MatrixXd centred = c.rowwise() - c.colwise().mean();
    const Eigen::VectorXd sd = (centred.colwise().squaredNorm() / n).cwiseSqrt().transpose();
    const Eigen::MatrixXd r = (centred.transpose() * centred / n).cwiseQuotient(sd * sd.transpose());
    double sameRow = 0, crossRow = 0, crossRowAbs = 0;
    int same = 0, cross = 0;
    for (int a = 0; a < fields; ++a)
        for (int b = a + 1; b < fields; ++b) {
            if (a / 4 == b / 4) {
                sameRow += r(a, b);
                ++same;
            } else {
                crossRow += r(a, b);
                crossRowAbs += std::abs(r(a, b));
                ++cross;
            }
        }
    INFO("mean correlation in a row " << sameRow / same << ", across rows " << crossRow / cross << " (|r| " << crossRowAbs / cross << ")");
    REQUIRE(same == 42);
    REQUIRE(sameRow / same == Approx(0.25).margin(0.07));
    REQUIRE(std::abs(crossRow / cross) < 0.04);
    REQUIRE(crossRowAbs / cross > 0.07);
}

TEST_CASE("face_params: the nose's parameters predict the chin's and the jaw's through the face-wide factors")
{
    // A linear regression over 4,000 faces of each chin and jaw parameter on the eight nose
    // parameters: with independent draws it explains about 8 / 4000 of the variance; with the
    // face-wide factors (weight 0.7, half of each variance shared) a good part.
    const int n = 4000;
    Eigen::MatrixXd nose(n, 9), jaw(n, 4);
    for (int i = 0; i < n; ++i) {
        const FaceParams p = sampleFaceParams(3, i);
        // Sex shifts the means of both regions; it is a regressor too, so only the factors remain.
        nose.row(i) << p.tipProtrusion, p.tipRise, p.dorsumHump, p.bridgeWidth, p.tipWidth, p.alaSize, p.nostrilSize, p.nasionDepth,
            p.female ? 1.0 : 0.0;
        jaw.row(i) << p.chinProjection, p.chinWidth, p.chinHeight, p.jawAngle;
    }
    Eigen::MatrixXd X(n, 10);
    X << nose, Eigen::VectorXd::Ones(n);
    double explained = 0;
    for (int j = 0; j < 4; ++j) {
        const Eigen::VectorXd y = jaw.col(j);
        Eigen::MatrixXd Xs(n, 2);
        Xs << nose.col(8), Eigen::VectorXd::Ones(n);
        // R^2 beyond what sex alone explains.
        const Eigen::VectorXd rs = y - Xs * Xs.colPivHouseholderQr().solve(y);
        const Eigen::VectorXd rf = y - X * X.colPivHouseholderQr().solve(y);
        const double gain = 1 - rf.squaredNorm() / rs.squaredNorm();
        INFO("chin and jaw parameter " << j << ": the nose explains " << gain << " of what sex leaves");
        CHECK(gain > 0.05);
        explained += gain / 4;
    }
    INFO("mean " << explained);
    REQUIRE(explained > 0.15);
}

// Population model of the synthetic faces: determinism, norms table (the portable generator
// itself is tested in tests/core/random.cpp).
#include "dataset/synth/face_params.h"
#include "test_common.h"

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
    for (int k = 0; k < kShapeFields; ++k) {
        INFO("field " << k);
        const double sign = k < 28 ? 1.0 : -1.0;
        for (double theta : { 0.0, 0.13, 0.3, 0.71 })
            for (double phi : { 0.5, 0.02, -0.4, -0.93 })
                REQUIRE(shapeField(k, -theta, phi) == Approx(sign * shapeField(k, theta, phi)).margin(1e-15));
    }
    // Each bump peaks at 1 at its centre: field 0 at (0, 0.55), field 28 (antisymmetric, row 0,
    // column 1) at +-0.3.
    REQUIRE(shapeField(0, 0, 0.55) == Approx(1.0).epsilon(1e-12));
    REQUIRE(shapeField(28, 0.3, 0.55) == Approx(1 - std::exp(-0.36 / 0.04)).epsilon(1e-12));

    const FaceParams p = sampleFaceParams(1, 5);
    REQUIRE(p.shapeModes.size() == static_cast<size_t>(kShapeFields));
    for (double theta : { -0.8, -0.2, 0.0, 0.45 })
        for (double phi : { 0.6, 0.1, -0.55, -1.0 }) {
            double sum = 0;
            for (int k = 0; k < kShapeFields; ++k)
                sum += p.shapeModes[static_cast<size_t>(k)] * shapeField(k, theta, phi);
            double meanSum = 0;
            for (int k = 0; k < kShapeFields; ++k)
                meanSum += shapeFieldMeans()[static_cast<size_t>(k)] * shapeField(k, theta, phi);
            const auto [both, means] = shapeFieldSums(p.shapeModes, shapeFieldMeans(), theta, phi);
            REQUIRE(both == Approx(sum).margin(1e-12));
            REQUIRE(means == Approx(meanSum).margin(1e-12));
        }
    // The population means: the 28 symmetric fields' are fitted (some non-zero), the 21
    // antisymmetric ones' are 0, so the mean face stays symmetric.
    REQUIRE(shapeFieldMeans().size() == static_cast<size_t>(kShapeFields));
    REQUIRE(std::count(shapeFieldMeans().begin(), shapeFieldMeans().begin() + 28, 0.0) < 28);
    REQUIRE(std::count(shapeFieldMeans().begin() + 28, shapeFieldMeans().end(), 0.0) == 21);
}

TEST_CASE("face_params: symmetric shape field coefficients are correlated along a lattice row, not across rows")
{
    // Fields 0..3 share row 0's factor (weight 0.5, so correlation 0.25); fields 0 and 4 do not.
    double s00 = 0, s01 = 0, s04 = 0, s0 = 0, s1 = 0, s4 = 0, s11 = 0, s44 = 0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
        const std::vector<double>& c = sampleFaceParams(2, i).shapeModes;
        s0 += c[0];
        s1 += c[1];
        s4 += c[4];
        s00 += c[0] * c[0];
        s11 += c[1] * c[1];
        s44 += c[4] * c[4];
        s01 += c[0] * c[1];
        s04 += c[0] * c[4];
    }
    auto sq = [](double x) { return x * x; };
    auto corr = [&](double sab, double sa, double sb, double saa, double sbb) {
        return (sab / n - sa / n * sb / n) / std::sqrt((saa / n - sq(sa / n)) * (sbb / n - sq(sb / n)));
    };
    // Standard error of a correlation from 4,000 samples is about 0.016.
    REQUIRE(corr(s01, s0, s1, s00, s11) == Approx(0.25).margin(0.06));
    REQUIRE(std::abs(corr(s04, s0, s4, s00, s44)) < 0.06);
}

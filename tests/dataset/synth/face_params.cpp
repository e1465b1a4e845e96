// Population model of the synthetic faces: determinism, norms table (the portable generator
// itself is tested in tests/core/random.cpp).
#include "dataset/synth/face_params.h"
#include "test_common.h"

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

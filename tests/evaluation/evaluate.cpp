// Tests of evaluation/evaluate: the scores against a direct recomputation, the exact case of a
// fully measured face, and bad input.
#include "evaluation/evaluate.h"

#include "core/error.h"
#include "stats/synthetic_faces.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::stats;
using namespace facesketch::evaluation;
using namespace facesketch::test;

namespace {

struct Setup {
    FaceModel model;
    Eigen::MatrixXd test;
};

// One component per segment and no cross-validation: the scores, not the model, are tested.
const Setup& setup()
{
    static const Setup s = [] {
        Random random(61);
        FaceModelOptions options;
        options.segmentation.clusters = 4;
        options.segmentation.minVertices = 30;
        options.components = { 1 };
        options.latentDim = 6;
        options.cleanUpDim = 8;
        options.mppca.restarts = 1;
        Setup out;
        out.model = trainFaceModel(syntheticFaces(random, 60), gridTriangles(), kNoseTip, options);
        out.test = syntheticFaces(random, 4);
        return out;
    }();
    return s;
}

} // namespace

TEST_CASE("evaluate: region scores match a direct recomputation")
{
    const Setup& s = setup();
    ObserveOptions options;
    for (int v = 0; v < kSide * kSide; ++v)
        if (s.model.segmentation.core(v) == s.model.segmentation.core(kNoseTip))
            options.region.push_back(v);
    const ObserveScore score = evaluateObserve(s.model, s.test, options);

    double mean = 0.0, worst = 0.0, meanFace = 0.0;
    std::vector<double> faceErrors, meanFaceErrors; // per face: the interval's unit
    for (Eigen::Index f = 0; f < s.test.rows(); ++f) {
        faceErrors.push_back(0.0);
        meanFaceErrors.push_back(0.0);
        Observations obs;
        for (int v : options.region)
            obs.addVertex(v, s.test.row(f).segment<3>(3 * v).transpose());
        const Eigen::VectorXd face = reconstruct(s.model, obs).face;
        for (int v = 0; v < kSide * kSide; ++v) {
            const double e = (face.segment<3>(3 * v) - s.test.row(f).segment<3>(3 * v).transpose()).norm();
            const double m = (s.model.meanFace.segment<3>(3 * v) - s.test.row(f).segment<3>(3 * v).transpose()).norm();
            mean += e;
            worst = std::max(worst, e);
            meanFace += m;
            faceErrors.back() += e;
            meanFaceErrors.back() += m;
        }
    }
    const double count = double(s.test.rows()) * kSide * kSide;
    CHECK(score.faces == 4);
    CHECK(std::abs(score.meanError - mean / count) < 1e-12);
    CHECK(score.maxError == worst);
    CHECK(std::abs(score.meanFaceMeanError - meanFace / count) < 1e-12);
    CHECK(std::abs(score.measuredFraction - double(options.region.size()) / (kSide * kSide)) < 1e-12);
    CHECK(score.meanError < score.meanFaceMeanError);
    // The ratio's interval is the bootstrap over faces (not vertices), and holds the ratio.
    const Interval expected = bootstrapRatio(faceErrors, meanFaceErrors);
    CHECK(score.ratioInterval.low == expected.low);
    CHECK(score.ratioInterval.high == expected.high);
    CHECK(score.ratioInterval.low < score.meanError / score.meanFaceMeanError);
    CHECK(score.meanError / score.meanFaceMeanError < score.ratioInterval.high);
}

TEST_CASE("evaluate: a fully measured face comes back exactly without clean-up")
{
    const Setup& s = setup();
    ObserveOptions options;
    options.fraction = 1.0;
    options.reconstruct.cleanUp = false;
    const ObserveScore score = evaluateObserve(s.model, s.test, options);
    CHECK(score.measuredFraction == 1.0);
    CHECK(score.maxError < 1e-9);
    CHECK(score.meanFaceMeanError > 1.0);
}

TEST_CASE("evaluate: rejects a bad fraction, region or face size")
{
    const Setup& s = setup();
    ObserveOptions options;
    options.fraction = 0.0;
    REQUIRE_THROWS_WITH(evaluateObserve(s.model, s.test, options), Catch::Contains("fraction"));
    options.fraction = 0.5;
    options.region = { kSide * kSide };
    REQUIRE_THROWS_WITH(evaluateObserve(s.model, s.test, options), Catch::Contains("region vertex"));
    REQUIRE_THROWS_AS(evaluateObserve(s.model, s.test.leftCols(9)), Error);
}

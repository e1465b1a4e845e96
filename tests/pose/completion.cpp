// Tests of pose/completion: completion from all FPs returns the pose itself, a mixture completes
// a non-linear family of poses that one PPCA cannot, and the number of components is chosen by
// the minimal-pose error.
#include "pose/completion.h"

#include "core/error.h"
#include "core/random.h"
#include "posed.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::pose;

namespace {

// Three FPs; three "poses" per identity: neutral (0), pose A (FP 0 moves 1 mm in x, FP 2 rises
// 5 mm), pose B (FP 0 moves 2 mm in x, FP 2 drops 5 mm). FP 2 is not a linear function of FP 0,
// so only a mixture with a component per pose completes it from FP 0 alone.
PoseSet toySet(int identities, std::uint64_t seed)
{
    Random random(seed);
    PoseSet s;
    s.fps = { { "2.1", "4.1", "8.3" }, { 0, 1, 2 } };
    s.vertexCount = 3;
    s.poseNames = { "neutral", "pose_a", "pose_b" };
    s.fpDisplacements = Eigen::MatrixXd::Zero(3 * identities, 9);
    for (int i = 0; i < identities; ++i) {
        s.identities.push_back({ "id" + std::to_string(i), dataset::Role::Train });
        const double scale = 1.0 + 0.05 * random.normal();
        for (int p = 0; p < 3; ++p) {
            Eigen::VectorXd row = 0.01 * random.normalMatrix(9, 1);
            if (p == 1) {
                row(0) += scale * 1.0;
                row(7) += scale * 5.0;
            } else if (p == 2) {
                row(0) += scale * 2.0;
                row(7) -= scale * 5.0;
            }
            s.fpDisplacements.row(3 * i + p) = row.transpose();
        }
    }
    s.meshDisplacements = s.fpDisplacements;
    s.neutrals = Eigen::MatrixXd::Zero(identities, 9);
    return s;
}

const std::vector<MinimalPose> kToyTable { { "pose_a", { "2.1" } }, { "pose_b", { "2.1" } } };

} // namespace

TEST_CASE("completion: a pose completed from all its FPs is itself")
{
    const test::PosedSynth& p = test::posedSynth();
    const PoseModel& m = test::posedModel();
    const int smile = p.test.poseIndex("smile_open");
    const Eigen::VectorXd truth = p.test.fpDisplacements.row(p.test.row(0, smile)).transpose();
    const Completion c = completePose(m, observeFps(m.fps, truth, m.fps.names));
    CHECK((c.fp - truth).cwiseAbs().maxCoeff() == 0.0);
    CHECK(c.posterior.sum() == Approx(1.0));
    CHECK(c.posterior.size() == m.completion.primary.size());
}

TEST_CASE("completion: a mixture completes a pose from one FP where one PPCA cannot")
{
    const PoseSet train = toySet(40, 3);
    const PoseSet validation = toySet(10, 4);
    CompletionOptions o;
    o.candidates = { 1, 3 };
    o.latentDims = { 2 };
    o.restarts = 2;
    const CompletionModel model = fitCompletion(train.fpDisplacements, validation, kToyTable, o);
    REQUIRE(model.scores.size() == 2);
    CHECK(model.scores[0].components == 1);
    CHECK(model.scores[1].components == 3);
    // K = 3 wins and rebuilds FP 2 of pose B from FP 0 alone to within noise.
    CHECK(model.primary.size() == 3);
    CHECK(model.alternative.size() == 1);
    CHECK(model.scores[1].minimalError < 0.3);
    CHECK(model.scores[0].minimalError > 3 * model.scores[1].minimalError);
    stats::Observations obs;
    obs.addVertex(0, Eigen::Vector3d(2.0, 0.0, 0.0));
    const Completion c = complete(model.primary, obs);
    CHECK(c.fp(7) == Approx(-5.0).margin(0.5));
    CHECK(c.fp.segment<3>(0) == Eigen::Vector3d(2.0, 0.0, 0.0));
}

TEST_CASE("completion: the candidates fitted on several threads give the scores and mixtures one thread gives")
{
    const PoseSet train = toySet(40, 3);
    const PoseSet validation = toySet(10, 4);
    CompletionOptions o;
    o.candidates = { 1, 2, 3, 4 };
    o.latentDims = { 1, 2 };
    o.threads = 1;
    const CompletionModel one = fitCompletion(train.fpDisplacements, validation, kToyTable, o);
    REQUIRE(one.scores.size() == 8);
    for (const int threads : { 3, 0 }) {
        o.threads = threads;
        const CompletionModel many = fitCompletion(train.fpDisplacements, validation, kToyTable, o);
        REQUIRE(many.scores.size() == one.scores.size());
        for (size_t i = 0; i < one.scores.size(); ++i) {
            CHECK(many.scores[i].components == one.scores[i].components);
            CHECK(many.scores[i].fitted == one.scores[i].fitted);
            CHECK(many.scores[i].latentDim == one.scores[i].latentDim);
            CHECK(many.scores[i].minimalError == one.scores[i].minimalError);
            CHECK(many.scores[i].logLikelihood == one.scores[i].logLikelihood);
        }
        CHECK(test::sameMixture(many.primary, one.primary));
        CHECK(test::sameMixture(many.alternative, one.alternative));
    }
}

TEST_CASE("completion: an FP seen only in a view gets its depth from the model")
{
    const PoseSet train = toySet(40, 3);
    CompletionOptions o;
    o.candidates = { 3 };
    o.latentDims = { 2 };
    const CompletionModel model = fitCompletion(train.fpDisplacements, toySet(10, 4), kToyTable, o);
    // FP 2 of pose A seen from the front: x and y only; its z must come back near 0, and FP 0's x near 1.
    stats::Observations obs;
    Eigen::Matrix<double, 2, 3> P;
    P << 1, 0, 0, 0, 1, 0;
    obs.addProjectedVertex(2, P, Eigen::Vector2d(0.0, 5.0));
    const Completion c = complete(model.primary, obs);
    CHECK(c.fp(6) == 0.0);
    CHECK(c.fp(7) == 5.0);
    CHECK(std::abs(c.fp(8)) < 0.1);
    CHECK(c.fp(0) == Approx(1.0).margin(0.1));
}

TEST_CASE("completion: bad observations and tables are refused")
{
    const PoseSet train = toySet(20, 3);
    CompletionOptions o;
    o.candidates = { 1 };
    o.latentDims = { 2 };
    const CompletionModel model = fitCompletion(train.fpDisplacements, train, kToyTable, o);
    stats::Observations outside;
    outside.addVertex(3, Eigen::Vector3d::Zero());
    REQUIRE_THROWS_AS(complete(model.primary, outside), Error);
    REQUIRE_THROWS_WITH(observeFps(train.fps, Eigen::VectorXd::Zero(9), { "9.3" }), Catch::Contains("9.3"));
    REQUIRE_THROWS_WITH(complete(stats::Mppca {}, stats::Observations {}), Catch::Contains("no components"));
    REQUIRE_THROWS_WITH(
        fitCompletion(train.fpDisplacements, train, { { "pose_c", { "2.1" } } }, o), Catch::Contains("no entry of the minimal-pose table"));
    Eigen::MatrixXd bad = train.fpDisplacements;
    bad(4, 2) = std::nan("");
    REQUIRE_THROWS_WITH(fitCompletion(bad, train, kToyTable, o), Catch::Contains("(4, 2)"));
}

TEST_CASE("completion: observation noise keeps a tight component for an FP drawn a little off its pose")
{
    // Two hand-made components over two FPs (d = 6, q = 1): a tight open pose (FP 0 10 mm down,
    // FP 1 5 mm down, sigma^2 = 0.01 mm^2, as a few distinct training poses fit) and a broad
    // rest pose at zero (sigma^2 = 9 mm^2). FP 0 drawn 1.5 mm short of the open pose.
    stats::Ppca open;
    open.mean = Eigen::VectorXd::Zero(6);
    open.mean(1) = -10.0;
    open.mean(4) = -5.0;
    open.W = Eigen::MatrixXd::Zero(6, 1);
    open.W(0, 0) = 0.1;
    open.sigma2 = 0.01;
    stats::Ppca rest = open;
    rest.mean.setZero();
    rest.sigma2 = 9.0;
    stats::Mppca mixture;
    mixture.components = { rest, open };
    mixture.priors = Eigen::Vector2d(0.5, 0.5);
    stats::Observations drawn;
    drawn.addVertex(0, Eigen::Vector3d(0.0, -8.5, 0.0));
    // Exact observations: 1.5 mm is 15 standard deviations of the open pose, so the rest pose wins.
    const Completion exact = complete(mixture, drawn);
    CHECK(exact.winner == 0);
    CHECK(std::abs(exact.fp(4)) < 1e-12);
    // With a reading noise of 1.5 mm the open pose explains the point, and FP 1 follows it.
    const Completion noisy = complete(mixture, drawn, 1.5);
    CHECK(noisy.winner == 1);
    CHECK(noisy.fp(4) == Approx(-5.0).margin(1e-9));
    CHECK(noisy.fp.segment<3>(0) == Eigen::Vector3d(0.0, -8.5, 0.0));
    REQUIRE_THROWS_WITH(complete(mixture, drawn, -1.0), Catch::Contains("observation noise -1 mm"));
    REQUIRE_THROWS_WITH(complete(mixture, drawn, std::nan("")), Catch::Contains("observation noise"));
}

// Tests of pose/pose_model: training on a posed synthetic set, posing a face, and refusing a face
// of another topology or with a NaN.
#include "pose/pose_model.h"

#include "core/error.h"
#include "posed.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::pose;

TEST_CASE("pose model: trained on the posed set, it keeps the training FP poses and the chosen mixtures")
{
    const PoseModel& m = test::posedModel();
    const test::PosedSynth& p = test::posedSynth();
    CHECK(m.vertexCount == p.dataset.manifest.vertexCount);
    CHECK(m.fps.names == p.train.fps.names);
    CHECK(m.poseNames == p.train.poseNames);
    CHECK(m.fpTraining == p.train.fpDisplacements);
    REQUIRE(m.fpTrainingPose.size() == static_cast<size_t>(m.fpTraining.rows()));
    CHECK(m.fpTrainingPose[37] == 1); // identity 1, pose 1
    CHECK(m.meanNeutral.isApprox(p.train.neutrals.colwise().mean().transpose()));
    REQUIRE(m.completion.scores.size() == 6); // K in {1, 2, 4} by q in {2, 8}
    double best = m.completion.scores[0].minimalError;
    for (const CompletionScore& s : m.completion.scores)
        best = std::min(best, s.minimalError);
    const auto chosen = std::find_if(m.completion.scores.begin(), m.completion.scores.end(), [&](const CompletionScore& s) {
        return s.fitted == m.completion.primary.size() && s.latentDim == m.completion.primary.components.front().latentDim();
    });
    REQUIRE(chosen != m.completion.scores.end());
    CHECK(chosen->minimalError == best);
    CHECK(m.completion.alternative.size() != m.completion.primary.size());
}

TEST_CASE("pose model: posedFace adds the mapped displacement to the face given")
{
    const PoseModel& m = test::posedModel();
    const test::PosedSynth& p = test::posedSynth();
    const Eigen::Index row = p.test.row(0, p.test.poseIndex("smile_open"));
    const Eigen::VectorXd fp = p.test.fpDisplacements.row(row).transpose();
    const Vertices neutral = asVertices(Eigen::VectorXd(p.test.neutrals.row(0).transpose()));
    const Vertices posed = posedFace(m, neutral, fp);
    CHECK((asVector(posed) - asVector(neutral) - mapToMesh(m.mapping, fp)).cwiseAbs().maxCoeff() < 1e-12);
    // The same FP pose on another face moves it the same way (a pose applies to any face).
    const Vertices other = asVertices(Eigen::VectorXd(m.meanNeutral));
    CHECK(((posedFace(m, other, fp) - other) - (posed - neutral)).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("pose model: a face of another topology or with a NaN is refused, naming it")
{
    const PoseModel& m = test::posedModel();
    Mesh face;
    face.V = asVertices(Eigen::VectorXd(m.meanNeutral));
    face.F = m.topology;
    REQUIRE_NOTHROW(checkFace(m, face, "face.ply"));
    Mesh fewer = face;
    fewer.V.conservativeResize(face.V.rows() - 1, 3);
    REQUIRE_THROWS_WITH(checkFace(m, fewer, "face.ply"), Catch::Contains("face.ply") && Catch::Contains("vertices"));
    Mesh flipped = face;
    std::swap(flipped.F(0, 1), flipped.F(0, 2));
    REQUIRE_THROWS_WITH(checkFace(m, flipped, "face.ply"), Catch::Contains("triangles differ"));
    Mesh nan = face;
    nan.V(5, 1) = std::nan("");
    REQUIRE_THROWS_WITH(checkFace(m, nan, "face.ply"), Catch::Contains("vertex 5"));
    REQUIRE_THROWS_AS(posedFace(m, nan.V, Eigen::VectorXd::Zero(3 * m.fpCount())), Error);
    REQUIRE_THROWS_AS(posedFace(m, fewer.V, Eigen::VectorXd::Zero(3 * m.fpCount())), Error);
}

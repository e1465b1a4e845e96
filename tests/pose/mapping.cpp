// Tests of pose/mapping: the statistical mapping rebuilds mesh poses that are a linear function
// of low-dimensional FP poses, beats RBF on the posed synthetic set, and RBF keeps its affine
// precision (a rest pose stays put, a translation moves everything).
#include "pose/mapping.h"

#include "core/error.h"
#include "core/random.h"
#include "posed.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::pose;

namespace {

double meanVertexError(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
    return (asVertices(a) - asVertices(b)).rowwise().norm().mean();
}

} // namespace

TEST_CASE("mapping: mesh poses that are linear in 3-dimensional FP poses are rebuilt exactly")
{
    Random random(9);
    const Eigen::Index n = 60, dFp = 12, dMesh = 300;
    const Eigen::MatrixXd Z = random.normalMatrix(n, 3);
    const Eigen::MatrixXd A = random.normalMatrix(3, dFp), B = random.normalMatrix(3, dMesh);
    const Eigen::MatrixXd fp = Z * A, mesh = Z * B;
    MappingOptions o;
    o.fpLatentDim = 3;
    o.meshLatentDim = 3;
    o.components = 1;
    o.jointLatentDim = 3;
    const PoseMapping m = fitMapping(fp, mesh, o);
    for (Eigen::Index i = 0; i < 5; ++i) {
        const Eigen::VectorXd mapped = mapToMesh(m, fp.row(i).transpose());
        // sigma^2 is floored above zero, so the latents shrink by a hair: exact to 1e-6 of the scale.
        CHECK((mapped - mesh.row(i).transpose()).cwiseAbs().maxCoeff() < 1e-6 * mesh.cwiseAbs().maxCoeff());
    }
    // A pose of the family not in the training set.
    const Eigen::RowVector3d z(0.3, -1.2, 0.7);
    CHECK((mapToMesh(m, (z * A).transpose()) - (z * B).transpose()).cwiseAbs().maxCoeff() < 1e-6 * mesh.cwiseAbs().maxCoeff());
}

TEST_CASE("mapping: mapToMesh into a buffer equals the returning form and refuses bad poses")
{
    const PoseModel& model = test::posedModel();
    const test::PosedSynth& p = test::posedSynth();
    const Eigen::VectorXd fp = p.test.fpDisplacements.row(p.test.row(0, p.test.poseIndex("surprise"))).transpose();
    Eigen::VectorXd out;
    mapToMesh(model.mapping, fp, out);
    CHECK(out == mapToMesh(model.mapping, fp));
    REQUIRE_THROWS_WITH(mapToMesh(model.mapping, Eigen::VectorXd::Zero(5)), Catch::Contains("5 values"));
    Eigen::VectorXd bad = fp;
    bad(7) = std::nan("");
    REQUIRE_THROWS_AS(mapToMesh(model.mapping, bad), Error);
    REQUIRE_THROWS_WITH(fitMapping(Eigen::MatrixXd::Zero(4, 6), Eigen::MatrixXd::Zero(5, 9), {}), Catch::Contains("4 FP poses but 5"));
}

TEST_CASE("mapping: on held-out identities the statistical mapping beats RBF (thesis fig. 5.19)")
{
    const PoseModel& model = test::posedModel();
    const test::PosedSynth& p = test::posedSynth();
    double statistical = 0.0, rbf = 0.0, neutral = 0.0;
    for (Eigen::Index i = 0; i < p.test.identityCount(); ++i)
        for (const char* name : { "anger", "smile_open", "jaw_open", "pucker", "viseme_O" }) {
            const Eigen::Index row = p.test.row(i, p.test.poseIndex(name));
            const Eigen::VectorXd truth = p.test.meshDisplacements.row(row).transpose();
            const Eigen::VectorXd fp = p.test.fpDisplacements.row(row).transpose();
            statistical += meanVertexError(mapToMesh(model.mapping, fp), truth);
            const Eigen::VectorXd face = p.test.neutrals.row(i).transpose();
            const Vertices warped = rbfPose(asVertices(face), p.test.fps, fp);
            rbf += meanVertexError(asVector(warped) - face, truth);
            neutral += meanVertexError(Eigen::VectorXd::Zero(truth.size()), truth);
        }
    INFO("statistical " << statistical << ", rbf " << rbf << ", neutral " << neutral);
    CHECK(statistical < rbf);
    CHECK(statistical < 0.5 * neutral);
}

TEST_CASE("mapping: RBF keeps the rest pose and moves the face rigidly for a translation")
{
    const test::PosedSynth& p = test::posedSynth();
    const Eigen::VectorXd face = p.test.neutrals.row(0).transpose();
    const Vertices V = asVertices(face);
    const Vertices same = rbfPose(V, p.test.fps, Eigen::VectorXd::Zero(3 * p.test.fps.size()));
    CHECK((same - V).cwiseAbs().maxCoeff() < 1e-9);
    Eigen::VectorXd shift(3 * p.test.fps.size());
    for (Eigen::Index f = 0; f < p.test.fps.size(); ++f)
        shift.segment<3>(3 * f) = Eigen::Vector3d(1.0, -2.0, 0.5);
    const Vertices moved = rbfPose(V, p.test.fps, shift);
    CHECK(((moved - V).rowwise() - Eigen::RowVector3d(1.0, -2.0, 0.5)).cwiseAbs().maxCoeff() < 1e-9);
}

// Tests of evaluation/pose_eval on a small posed synthetic set: the records are the ones the
// issue names, the neutral baseline is the mean displacement, the statistical mapping beats RBF
// and completion from minimal FPs beats leaving the face neutral.
#include "evaluation/pose_eval.h"

#include "core/error.h"
#include "dataset/synth/synth_dataset.h"
#include "pose/minimal_poses.h"
#include "test_common.h"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>

using namespace facesketch;

TEST_CASE("pose eval: records of completion and mapping on held-out identities, against hand-computed neutral error")
{
    test::TempDir dir;
    dataset::SynthOptions s;
    s.identities = 30; // 22 train, 6 contour, 2 test
    s.poses = true;
    s.seed = 8;
    dataset::writeSynthDataset(dir / "posed", s);
    const dataset::Dataset ds = dataset::openDataset(dir / "posed");
    const pose::PoseSet all = pose::loadPoseSet(ds, { dataset::Role::Train, dataset::Role::Contour, dataset::Role::Test });
    const pose::PoseSet train = pose::selectRole(all, dataset::Role::Train);
    const pose::PoseSet contour = pose::selectRole(all, dataset::Role::Contour);
    const pose::PoseSet test = pose::selectRole(all, dataset::Role::Test);
    const char* source = std::getenv("FACESKETCH_SOURCE_DIR");
    const auto minimal = pose::readMinimalPoses(std::filesystem::path(source ? source : ".") / "assets" / "minimal-poses.json");
    // The default options: the claim under test is the (completion under half the neutral error).
    const pose::PoseModel model = pose::trainPoseModel(train, contour, minimal, {});
    const evaluation::PoseEvaluation e = evaluation::evaluatePoses(model, test, minimal);

    REQUIRE(e.identities == test.identityCount());
    REQUIRE(e.results.size() == 5);
    auto find = [&](const std::string& task, const std::string& method) {
        for (const auto& r : e.results)
            if (r.task == task && r.method == method)
                return r;
        FAIL("no record " << task << " " << method);
        return evaluation::PoseEvalRecord {};
    };
    const auto neutral = find("neutral", "neutral");
    CHECK(neutral.poses == 35);
    CHECK(neutral.ratio == 1.0);
    double expected = 0.0;
    for (Eigen::Index r = 0; r < test.meshDisplacements.rows(); ++r)
        expected += asVertices(Eigen::VectorXd(test.meshDisplacements.row(r).transpose())).rowwise().norm().mean();
    expected /= static_cast<double>(test.identityCount() * 35); // neutral rows add 0
    CHECK(neutral.meanMm == Approx(expected).epsilon(1e-12));

    const auto statistical = find("mapping", "statistical"), rbf = find("mapping", "rbf");
    CHECK(statistical.poses == 35);
    CHECK(statistical.ratio == Approx(statistical.meanMm / neutral.meanMm).epsilon(1e-12));
    CHECK(statistical.meanMm < rbf.meanMm);
    const auto completion = find("completion", "mixture");
    CHECK(completion.poses == 35);
    CHECK(completion.ratio < 0.5);
    CHECK(find("completion", "alternative").poses == 35);
    CHECK(e.perPose.size() == 5 * 35);

    pose::PoseSet other = test;
    other.vertexCount += 1;
    REQUIRE_THROWS_WITH(evaluation::evaluatePoses(model, other, minimal), Catch::Contains("topology"));
}

// Posing from simulated pose strokes (eval poses part (c)): strokes trace the pose's own
// contours, and posing a held-out face by them beats leaving it neutral.
#include "pose/stroke_eval.h"

#include "core/error.h"
#include "pose_fixture.h"
#include "test_common.h"

using namespace facesketch;
using namespace facesketch::pose;

namespace {

/// Identity 20 of the posing world in neutral and three poses, as a PoseSet.
PoseSet heldOut(const test::PoseWorld& w, const std::vector<std::string>& names)
{
    PoseSet set;
    set.fps = w.model.fps;
    set.vertexCount = w.model.vertexCount;
    set.topology = w.model.topology;
    set.poseNames = names;
    set.identities = { { "face_0020", dataset::Role::Test } };
    set.neutrals = asVector(w.neutral.V).transpose();
    set.meshDisplacements.resize(static_cast<Eigen::Index>(names.size()), 3 * set.vertexCount);
    set.fpDisplacements.resize(static_cast<Eigen::Index>(names.size()), 3 * set.fps.size());
    for (std::size_t p = 0; p < names.size(); ++p) {
        const Vertices& posed = w.pose(names[p]).V;
        set.meshDisplacements.row(static_cast<Eigen::Index>(p)) = (asVector(posed) - asVector(w.neutral.V)).transpose();
        set.fpDisplacements.row(static_cast<Eigen::Index>(p)) = (set.fps.gather(posed) - set.fps.gather(w.neutral.V)).transpose();
    }
    return set;
}

} // namespace

TEST_CASE("pose stroke eval: simulated strokes trace the pose's contours in the front view")
{
    const test::PoseWorld& w = test::poseWorld();
    const auto& contours = w.topology.labels.contours;
    PoseStrokeSimulation exact;
    exact.noisePx = 0;
    const Mesh& smile = w.pose("smile_open");
    const auto strokes = simulatePoseStrokes(smile, w.neutral, contours, exact);
    REQUIRE(strokes.size() == 4);
    const Camera camera = orbitCamera(strokes[0].view);
    const std::vector<int>& lip = contours.at("lip_upper_outer");
    REQUIRE(strokes[0].points.size() == lip.size());
    for (std::size_t i = 0; i < lip.size(); ++i) {
        const glm::dvec3 p = camera.project({ smile.V(lip[i], 0), smile.V(lip[i], 1), smile.V(lip[i], 2) });
        REQUIRE(strokes[0].points[i].x == p.x);
        REQUIRE(strokes[0].points[i].y == p.y);
    }
    // Jitter moves points by about noisePx, deterministically for a seed.
    const auto noisy = simulatePoseStrokes(smile, w.neutral, contours);
    REQUIRE(noisy[0].points[3].x != strokes[0].points[3].x);
    REQUIRE(std::abs(noisy[0].points[3].x - strokes[0].points[3].x) < 6.0);
    REQUIRE(simulatePoseStrokes(smile, w.neutral, contours)[0].points[3].x == noisy[0].points[3].x);
    PoseStrokeSimulation missing;
    missing.contours = { "lip_upper_outer", "ear" };
    REQUIRE_THROWS_WITH(simulatePoseStrokes(smile, w.neutral, contours, missing), Catch::Contains("no contour ear"));
}

TEST_CASE("pose stroke eval: posing a held-out face from its poses' strokes beats leaving it neutral")
{
    const test::PoseWorld& w = test::poseWorld();
    const PoseSet test = heldOut(w, { "neutral", "smile_open", "jaw_open", "anger" });
    const StrokePoseEvaluation e = evaluateStrokePoses(w.model, test, w.topology.labels.contours);
    REQUIRE(e.record.task == "strokes");
    REQUIRE(e.record.poses == 3);
    REQUIRE(e.perPose.size() == 3);
    REQUIRE(e.strokes == 12);
    double sum = 0, neutral = 0;
    for (const auto& p : e.perPose) {
        INFO(p.pose << ": posed " << p.meanMm << " mm, neutral " << p.neutralMm << " mm");
        REQUIRE(p.neutralMm > 0);
        sum += p.meanMm;
        neutral += p.neutralMm;
    }
    REQUIRE(e.record.meanMm == Approx(sum / 3).epsilon(1e-12));
    REQUIRE(e.record.ratio == Approx(sum / neutral).epsilon(1e-12));
    INFO("ratio " << e.record.ratio << ", " << e.refused << " strokes refused");
    REQUIRE(e.record.ratio < 0.85);
    // The open smile and the open jaw move the face most; their strokes must recover much of it.
    REQUIRE(e.perPose[0].meanMm < 0.85 * e.perPose[0].neutralMm);
    REQUIRE(e.perPose[1].meanMm < 0.7 * e.perPose[1].neutralMm);
}

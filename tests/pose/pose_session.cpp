// Posing by a session's actions (thesis 5.3-5.5): strokes along a pose's own lips pose the face
// towards it, undo and redo are exact, bad actions change nothing and are named as the file does.
#include "pose/pose_session.h"

#include "core/error.h"
#include "pose_fixture.h"
#include "test_common.h"

#include <set>

using namespace facesketch;
using namespace facesketch::pose;

namespace {

std::vector<sketch::Stroke> lipStrokes(const test::PoseWorld& w, const std::string& pose)
{
    const auto& contours = w.topology.labels.contours;
    return { test::traceStroke(w.pose(pose), contours.at("lip_upper_outer"), w.front),
        test::traceStroke(w.pose(pose), contours.at("lip_lower_outer"), w.front) };
}

} // namespace

TEST_CASE("pose session: strokes along the open smile's lips find the lip FPs and pose the face towards the smile")
{
    const test::PoseWorld& w = test::poseWorld();
    PoseEditor editor(w.model, w.neutral);
    REQUIRE(editor.face().V == w.neutral.V);
    for (const sketch::Stroke& s : lipStrokes(w, "smile_open"))
        editor.apply(test::strokeAction(s));
    REQUIRE(editor.reading().strokeGroup == std::vector<std::string> { "upper_lip", "lower_lip" });
    std::set<std::string> found;
    for (const auto& fp : editor.reading().fps)
        found.insert(fp.name);
    for (const std::string name : { "8.1", "8.2", "8.3", "8.4" })
        REQUIRE(found.count(name) == 1);
    const Mesh& smile = w.pose("smile_open");
    const double before = test::meanError(w.neutral.V, smile.V);
    const double after = test::meanError(editor.face().V, smile.V);
    // What the completion makes of the same FPs drawn perfectly: the smile's own FPs, seen
    // from the front. The strokes can do no better; they must come close.
    const Eigen::VectorXd trueFp = w.model.fps.gather(smile.V) - w.model.fps.gather(w.neutral.V);
    stats::Observations perfect;
    const Eigen::Matrix<double, 2, 3> P = editor.reading().fps.front().plane;
    for (const auto& fp : editor.reading().fps)
        perfect.addProjectedVertex(fp.fp, P, P * trueFp.segment<3>(3 * fp.fp));
    const double ideal = test::meanError(posedFace(w.model, w.neutral.V, completePose(w.model, perfect).fp), smile.V);
    INFO("mean error: neutral " << before << " mm, posed by the strokes " << after << " mm, by the same FPs drawn perfectly " << ideal
                                << " mm");
    REQUIRE(after < 0.85 * before);
    // The best point of a cluster along a stroke leans towards the cluster's mean (thesis 5.3
    // takes the likeliest point): the lips' mid-points land up to 1.5 mm inwards, which costs
    // about 0.5 mm over the face.
    REQUIRE(after < ideal + 0.75);
    for (const auto& fp : editor.reading().fps) {
        const Eigen::Vector3d target = smile.V.row(w.model.fps.vertices[static_cast<std::size_t>(fp.fp)]).transpose();
        REQUIRE((P * (fp.position - target)).norm() < 1.5);
    }
    // The identified FPs keep what the strokes said in their plane; the depth is the model's.
    const Vertices fps = editor.featurePointPositions();
    const Camera camera = orbitCamera(w.front);
    for (const auto& fp : editor.reading().fps) {
        const glm::dvec3 drawn = camera.project({ fp.position.x(), fp.position.y(), fp.position.z() });
        const glm::dvec3 posed = camera.project({ fps(fp.fp, 0), fps(fp.fp, 1), fps(fp.fp, 2) });
        REQUIRE(std::abs(drawn.x - posed.x) < 1e-6);
        REQUIRE(std::abs(drawn.y - posed.y) < 1e-6);
    }
}

TEST_CASE("pose session: undo and redo restore bit-identical states, and a bad action changes nothing")
{
    const test::PoseWorld& w = test::poseWorld();
    const auto smile = lipStrokes(w, "smile_open");
    const auto pucker = lipStrokes(w, "pucker");
    PoseEditor a(w.model, w.neutral);
    a.apply(test::strokeAction(smile[0]));
    a.apply(test::keyframeAction(0.0));
    const Vertices afterKey = a.face().V;
    a.apply(test::clearAction());
    REQUIRE(a.face().V == w.neutral.V);
    a.apply(test::strokeAction(pucker[0]));
    a.apply(test::keyframeAction(1.0));
    REQUIRE(a.keyframes().size() == 2);
    REQUIRE(a.undo());
    REQUIRE(a.undo());
    REQUIRE(a.undo());
    REQUIRE(a.face().V == afterKey);
    REQUIRE(a.keyframes().size() == 1);
    REQUIRE(a.redo());
    REQUIRE(a.redo());
    const Vertices puckered = a.face().V;
    PoseEditor b(w.model, w.neutral);
    for (const auto& action :
        { test::strokeAction(smile[0]), test::keyframeAction(0.0), test::clearAction(), test::strokeAction(pucker[0]) })
        b.apply(action);
    REQUIRE(b.face().V == puckered);
    REQUIRE(b.pose() == a.pose());

    // A stroke on the forehead's top edge, far from every cluster: refused, nothing changed.
    sketch::Stroke off = smile[0];
    for (auto& p : off.points)
        p.y = 5;
    REQUIRE_THROWS_WITH(b.apply(test::strokeAction(off)), Catch::StartsWith("pose stroke 1 hits no feature point cluster"));
    REQUIRE(b.face().V == puckered);
    REQUIRE_FALSE(b.redo());
    REQUIRE_THROWS_WITH(b.apply(test::keyframeAction(0.0)), Catch::Contains("keyframe at 0 s already"));
    REQUIRE_THROWS_WITH(b.apply(test::keyframeAction(-1.0)), Catch::Contains("keyframe: time -1"));
    REQUIRE(b.keyframes().size() == 1);
    REQUIRE_THROWS_WITH(b.timeline(), Catch::Contains("1 keyframe(s)"));
}

TEST_CASE("pose session: keyframes move and are deleted with their poses, undoably, and bad edits change nothing")
{
    const test::PoseWorld& w = test::poseWorld();
    const auto smile = lipStrokes(w, "smile_open");
    PoseEditor e(w.model, w.neutral);
    e.apply(test::keyframeAction(0.0)); // the neutral pose
    e.apply(test::strokeAction(smile[0]));
    e.apply(test::keyframeAction(1.0)); // the smile
    const Eigen::VectorXd smilePose = e.pose();
    REQUIRE(smilePose.norm() > 0);
    const Vertices face = e.face().V;
    e.apply(test::moveKeyframeAction(1.0, 2.5));
    REQUIRE(e.keyframes().size() == 2);
    REQUIRE(e.face().V == face); // editing the timeline does not pose the face
    const Timeline moved = e.timeline();
    REQUIRE(moved.end() == 2.5);
    REQUIRE(moved.sample(2.5) == smilePose);
    REQUIRE(moved.sample(0.0).norm() == 0);
    // Bad edits: refused, nothing changed.
    REQUIRE_THROWS_WITH(e.apply(test::moveKeyframeAction(1.0, 3.0)), Catch::StartsWith("keyframe move: there is no keyframe at 1 s"));
    REQUIRE_THROWS_WITH(
        e.apply(test::moveKeyframeAction(2.5, 0.0)), Catch::StartsWith("keyframe move: there is a keyframe at 0 s already"));
    REQUIRE_THROWS_WITH(e.apply(test::moveKeyframeAction(2.5, -1.0)), Catch::StartsWith("keyframe move: time -1"));
    REQUIRE_THROWS_WITH(e.apply(test::deleteKeyframeAction(7.0)), Catch::StartsWith("keyframe delete: there is no keyframe at 7 s"));
    REQUIRE(e.timeline().end() == 2.5);
    e.apply(test::deleteKeyframeAction(0.0));
    REQUIRE(e.keyframes().size() == 1);
    REQUIRE(e.keyframes()[0].time == 2.5);
    REQUIRE(e.keyframes()[0].fp == smilePose);
    REQUIRE(e.undo());
    REQUIRE(e.keyframes().size() == 2);
    REQUIRE(e.undo());
    REQUIRE(e.timeline().end() == 1.0);
    REQUIRE(e.timeline().sample(1.0) == smilePose);
    REQUIRE(e.redo());
    REQUIRE(e.timeline().end() == 2.5);
}

TEST_CASE("pose session: replay names a bad action as the file does, and the timeline passes through the keyframes")
{
    const test::PoseWorld& w = test::poseWorld();
    sketch::Session session;
    session.actions.resize(1); // one shape strokes before the posing
    const auto smile = lipStrokes(w, "smile_open");
    for (auto a : { test::strokeAction(smile[0]), test::keyframeAction(0.5), test::clearAction(), test::keyframeAction(2.0) }) {
        a.afterStrokes = 1;
        session.poseActions.push_back(a);
    }
    PoseEditor editor(w.model, w.neutral);
    replayPoseActions(editor, session);
    const Timeline timeline = editor.timeline();
    REQUIRE(timeline.sample(0.5) == editor.keyframes()[0].fp);
    REQUIRE(timeline.sample(2.0) == Eigen::VectorXd::Zero(3 * w.model.fpCount()));
    const std::vector<double> times = frameTimes(timeline, 4.0);
    REQUIRE(times == std::vector<double> { 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0 });
    REQUIRE(frameTimes(timeline, 3.0).back() == 2.0);
    REQUIRE(frameTimes(timeline, 3.0).size() == 6); // 0.5, 0.83, 1.17, 1.5, 1.83 and the end
    REQUIRE_THROWS_WITH(frameTimes(timeline, 0.0), Catch::Contains("frames per second: 0"));

    sketch::Stroke off = smile[0];
    for (auto& p : off.points)
        p.y = 5;
    session.poseActions.insert(session.poseActions.begin() + 2, test::strokeAction(off));
    session.poseActions[2].afterStrokes = 1;
    PoseEditor again(w.model, w.neutral);
    REQUIRE_THROWS_WITH(
        replayPoseActions(again, session), Catch::StartsWith("actions[3] (pose-stroke): pose stroke 1 hits no feature point"));

    Mesh other = w.neutral;
    other.V(3, 1) = std::nan("");
    REQUIRE_THROWS_WITH(PoseEditor(w.model, other), Catch::Contains("the face to pose: vertex 3"));
    other = w.neutral;
    other.F.conservativeResize(other.F.rows() - 1, 3);
    REQUIRE_THROWS_WITH(PoseEditor(w.model, other), Catch::Contains("the face to pose: its triangles differ"));
}

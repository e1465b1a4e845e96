// A played timeline as a glTF animation: every exported frame is the frame the TimelinePlayer
// sampled at its time, and the written .glb gives those frames back to a client.
#include "pose/animation.h"

#include "core/error.h"
#include "io/gltf_fixture.h"
#include "pose/pose_session.h"
#include "pose_fixture.h"
#include "test_common.h"

using namespace facesketch;
using namespace facesketch::pose;

TEST_CASE("pose animation: the exported glb shows at each frame time the frame the timeline player sampled there")
{
    const test::PoseWorld& w = test::poseWorld();
    PoseEditor editor(w.model, w.neutral);
    sketch::PoseAction key;
    key.kind = sketch::PoseActionKind::Keyframe;
    editor.apply(key);
    sketch::PoseAction stroke;
    stroke.stroke = test::traceStroke(w.pose("smile_open"), w.topology.labels.contours.at("lip_upper_outer"), w.front);
    editor.apply(stroke);
    key.time = 0.8;
    editor.apply(key);
    const Timeline timeline = editor.timeline();
    const std::vector<double> times = frameTimes(timeline, 10.0);
    REQUIRE(times.size() == 9);
    const GltfAnimation animation = timelineAnimation(w.model, timeline, w.neutral, times);
    REQUIRE(animation.times == times);
    REQUIRE(animation.face.V == w.neutral.V);
    TimelinePlayer player(w.model, timeline, w.neutral);
    for (std::size_t k = 0; k < times.size(); ++k)
        REQUIRE(animation.frames[k] == player.frame(times[k]));
    // The last frame is the smile keyframe's face, away from the rest face (the check above is
    // not vacuous): 0.44 mm on average over the face from one lip stroke (v15's fixture; over
    // 0.5 before), where the frames' equality is exact.
    REQUIRE(test::meanError(animation.frames.back(), w.neutral.V) > 0.2);

    test::TempDir dir;
    writeGlb(dir / "a.glb", animation);
    const tinygltf::Model model = test::loadGlb(dir / "a.glb");
    for (std::size_t k = 0; k < times.size(); ++k) {
        INFO("frame " << k);
        REQUIRE((test::morphedFace(model, k, 0.0) - animation.frames[k]).cwiseAbs().maxCoeff() < 1e-4);
    }
    REQUIRE_THROWS_WITH(timelineAnimation(w.model, timeline, w.neutral, { 0.9 }), Catch::Contains("outside the timeline"));
    REQUIRE_THROWS_WITH(timelineAnimation(w.model, timeline, w.neutral, {}), Catch::Contains("no frame times"));
}

#pragma once
// A small posing world for the tests of engine/pose's stroke and session part: the 36 synthetic
// poses of 8 low-resolution identities (in memory, no dataset on disk), a pose model trained on
// them with few components, and identity 20 (not among them) as the face to pose, with its own
// poses as the answers. Built once per process (ctest runs each test case in its own process).

#include "dataset/synth/face_generator.h"
#include "geometry/camera.h"
#include "pose/pose_model.h"
#include "sketch/session.h"
#include "sketch/stroke.h"

#include <string>
#include <vector>

namespace facesketch::test {

struct PoseWorld {
    dataset::FaceTopology topology;
    pose::PoseModel model;
    Mesh neutral;            ///< identity 20, neutral
    std::vector<Mesh> poses; ///< identity 20 in each pose of model.poseNames
    OrbitView front;         ///< an 800 by 800 front view framing the neutral face

    const Mesh& pose(const std::string& name) const;
};

const PoseWorld& poseWorld();

/// A pose stroke tracing `contour` (vertex indices) of `face` in `view`: the vertices' pixels.
sketch::Stroke traceStroke(const Mesh& face, const std::vector<int>& contour, const OrbitView& view);

/// Pose-session actions as the app and the session file make them (sketch/session.h).
sketch::PoseAction strokeAction(const sketch::Stroke& stroke);
sketch::PoseAction keyframeAction(double time);
sketch::PoseAction moveKeyframeAction(double time, double to);
sketch::PoseAction deleteKeyframeAction(double time);
sketch::PoseAction clearAction();

/// Mean distance between corresponding vertices (mm).
double meanError(const Vertices& a, const Vertices& b);

} // namespace facesketch::test

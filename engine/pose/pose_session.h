#pragma once
// Posing a face by its session's pose actions (thesis 5.3-5.5; docs/session-format.md, version
// 2): pose strokes are read for feature points (stroke_fps.h), the pose is completed from them
// (completion.h, the primary or alternative mixture) and rebuilt on the face by the mapping
// (mapping.h); keyframes snapshot the completed pose at a time, and the timeline through them
// (timeline.h) is played frame by frame.
//
// One pose stroke, in order:
// 1. projected (sketch/projection.h) onto its surface of the face as currently posed, the face
//    the user saw when drawing it; its points keep that depth for good;
// 2. all pose strokes since the last clear are read together (stroke_fps.h identifyFps);
// 3. the identified FPs' sketch-plane displacements from the neutral face are the completion's
//    observations (their depth is the completion's, eq. 4.21);
// 4. the completed FP pose is mapped to the mesh: face = neutral + Psi(pose).
// Undo and redo restore the stored state after k actions, so the state after k actions is
// bit-identical whether reached directly or by undoing later ones.

#include "core/mesh.h"
#include "pose/pose_model.h"
#include "pose/stroke_fps.h"
#include "pose/timeline.h"
#include "sketch/session.h"

#include <Eigen/Core>
#include <vector>

namespace facesketch::pose {

struct PoseStrokeOptions {
    double maxGapPx = 4.0; ///< stroke densification (sketch/projection.h densify)
    double tension = 0.5;  ///< of the densifying spline
    FpClusterOptions clusters;
    FpReadingOptions reading;
    /// Standard deviation (mm) of a read FP's error, the completion's observation noise
    /// (completion.h complete): a hand-drawn stroke is a pixel or two off, and step 5 picks the
    /// best point per FP along it, a millimetre or two from the FP's true place (the clusters'
    /// minStdMm, the same 1.5 mm).
    double readingNoiseMm = 1.5;
};

class PoseEditor {
public:
    /// Poses `neutral` (the model's topology, mm; checkFace) with `model`, which it keeps a
    /// reference to: keep it alive. The initial state is the neutral face, no keyframes.
    PoseEditor(const PoseModel& model, const Mesh& neutral, const PoseStrokeOptions& options = {});

    /// Applies one action and forgets any undone ones. Throws Error, leaving the state as it was,
    /// if a stroke is invalid or hits no cluster, a keyframe's (or a move's new) time is not
    /// finite, negative or already a keyframe's, or a move or delete names no keyframe's time.
    void apply(const sketch::PoseAction& action);
    /// Back to the state before the last action; false (and no change) if there is none.
    bool undo();
    /// Re-applies the last undone action's state; false (and no change) if none.
    bool redo();

    /// The face as posed now, #V by 3 (mm), and its triangles.
    const Mesh& face() const { return states_[current_].face; }
    /// The completed FP pose now: 3F displacements from the neutral (zero when nothing is drawn).
    const Eigen::VectorXd& pose() const { return states_[current_].pose; }
    /// The reading of the pose strokes since the last clear.
    const FpReading& reading() const { return states_[current_].reading; }
    /// The completion's most probable component (-1 when nothing is drawn).
    int component() const { return states_[current_].component; }
    const std::vector<Keyframe>& keyframes() const { return states_[current_].keyframes; }
    const Mesh& neutral() const { return neutral_; }
    const PoseModel& model() const { return model_; }
    /// The FP positions on the current face (F by 3, mm): neutral FPs plus pose().
    Vertices featurePointPositions() const;

    /// The timeline through the keyframes (timeline.h). Throws Error for fewer than two.
    Timeline timeline(double tension = 0.0) const;

private:
    struct State {
        std::vector<PoseStrokePoints> strokes;
        FpReading reading;
        Eigen::VectorXd pose;
        int component = -1;
        Mesh face;
        std::vector<Keyframe> keyframes;
    };

    const PoseModel& model_;
    Mesh neutral_;
    PoseStrokeOptions options_;
    FpClusters clusters_;
    std::vector<State> states_;
    std::size_t current_ = 0;
};

/// Applies every pose action of `session` in order. An Error names the action as the file does
/// ("actions[6] (pose-stroke): pose stroke 1 hits no feature point cluster ...").
void replayPoseActions(PoseEditor& editor, const sketch::Session& session);

/// The frame times of a timeline played at `fps` frames per second: begin, begin + 1/fps, ...,
/// and end itself (a last step shorter than 1/fps if need be). Throws Error for fps <= 0 or
/// more than 100,000 frames.
std::vector<double> frameTimes(const Timeline& timeline, double fps);

} // namespace facesketch::pose

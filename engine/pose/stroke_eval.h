#pragma once
// Posing from simulated pose strokes: part (c) of `facesketch eval poses` (issue 13), and the
// strokes `bench pose` times (pose_stroke_ms_<V>v).
//
// A pose's strokes, as a user describing it would draw them: its feature contours (the
// dataset's labelled `lip_upper_outer`, `lip_lower_outer`, `eyebrow_l`, `eyebrow_r`, each
// tracing the pose's own vertices in order) seen from the front of the neutral face, each point
// jittered by N(0, noisePx^2) pixels. They are drawn on the neutral face being posed (surface
// "face") and applied in order by a PoseEditor (pose_session.h); a stroke the editor refuses
// (it hits no cluster) is left out, as a user would see it refused and not draw it again.

#include "core/mesh.h"
#include "evaluation/pose_eval.h"
#include "pose/pose_model.h"
#include "pose/pose_session.h"
#include "sketch/stroke.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace facesketch::pose {

struct PoseStrokeSimulation {
    std::vector<std::string> contours { "lip_upper_outer", "lip_lower_outer", "eyebrow_l", "eyebrow_r" };
    int imageSize = 800;  ///< square viewport, pixels
    double noisePx = 1.0; ///< jitter of every point, pixels (standard deviation)
    std::uint64_t seed = 1;
};

/// The strokes tracing `posed`'s contours (vertex paths in its numbering, e.g. a manifest's
/// `contours`) in the front view framing `neutral`. Throws Error naming a contour `contours`
/// lacks or a vertex outside the face, or for negative noise.
std::vector<sketch::Stroke> simulatePoseStrokes(const Mesh& posed, const Mesh& neutral,
    const std::map<std::string, std::vector<int>>& contours, const PoseStrokeSimulation& options = {});

struct StrokePoseEvaluation {
    /// {"task": "strokes", "method": "statistical", poses, mean_mm, ratio}: the mean over every
    /// (test identity, pose but neutral) of the mean vertex error of the face posed by its
    /// simulated strokes, and its ratio to leaving the face neutral on the same pairs.
    evaluation::PoseEvalRecord record;
    std::vector<evaluation::PosePoseError> perPose;
    int strokes = 0; ///< strokes drawn, and how many the editor refused
    int refused = 0;
};

/// Part (c) on every identity of `test` (pose_data.h) and every pose but "neutral". Throws Error
/// if `test` has no identity or another topology or FPs than the model.
StrokePoseEvaluation evaluateStrokePoses(const PoseModel& model, const PoseSet& test,
    const std::map<std::string, std::vector<int>>& contours, const PoseStrokeSimulation& simulation = {},
    const PoseStrokeOptions& options = {});

} // namespace facesketch::pose

#pragma once
// pose_stroke_ms_<V>v, for `facesketch bench pose` (issue 13; goal under 50 ms at 6,000
// vertices): pose strokes to a posed face, i.e. for each stroke its projection onto the face,
// reading all strokes so far for FPs, completing the pose and mapping it to the mesh
// (pose/pose_session.h PoseEditor::apply).

#include "core/mesh.h"
#include "pose/pose_model.h"

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace facesketch::app {

/// Poses `neutral` (the model's topology) by the simulated pose strokes of `posed`
/// (pose/stroke_eval.h simulatePoseStrokes: its lips and brows from the front), `repeat` times
/// with a fresh editor, and prints `pose_stroke_ms_<V>v <median ms per stroke> ms` with a
/// `# ...` line of context. `contours` are the dataset's labelled contours (manifest).
void benchPoseStrokes(const pose::PoseModel& model, const Mesh& neutral, const Mesh& posed,
    const std::map<std::string, std::vector<int>>& contours, int repeat, std::ostream& out);

} // namespace facesketch::app

#pragma once
// A played timeline as files (thesis 5.5; `facesketch animate`): the frames a TimelinePlayer
// samples, as a glTF animation (io/gltf_export.h: one morph target per sampled frame, so every
// frame is reproduced exactly) or as rendered PNG frames.
//
// The whole head is one morph-animated mesh: the pose mapping moves every vertex, the rigid
// parts (eyes, teeth) with the rest (their motion is in the training poses), so no part needs
// a node transform of its own and nothing is approximated.

#include "core/mesh.h"
#include "io/gltf_export.h"
#include "pose/pose_model.h"
#include "pose/timeline.h"

#include <filesystem>
#include <string>
#include <vector>

namespace facesketch::pose {

/// The frames of `timeline` played on `neutral` (TimelinePlayer) at `times` (seconds inside the
/// timeline), with their vertex normals (geometry/normals.h), as a glTF animation whose rest
/// shape is `neutral` and whose keys are the times. Throws Error as TimelinePlayer (a face of
/// another topology, a time outside the timeline) or for no times.
GltfAnimation timelineAnimation(const PoseModel& model, const Timeline& timeline, const Mesh& neutral, const std::vector<double>& times);

/// Renders every frame of `animation` (the face in each frame, front view framing the rest face,
/// `size` pixels square) into `folder` as frame_0000.png, frame_0001.png, ... Creates the folder;
/// refuses (Error) a folder that exists and is not empty, before writing anything.
void writeFramePngs(const GltfAnimation& animation, const std::filesystem::path& folder, int size = 512);

} // namespace facesketch::pose

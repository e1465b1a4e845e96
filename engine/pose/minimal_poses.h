#pragma once
// The table of minimal incomplete poses (thesis 5.4): for each pose, the few feature points
// that a user would draw to ask for it, e.g. three lowered points of one brow for anger
// (fig. 5.12) or one lip corner for an open smile (fig. 5.13). The completion mixture is
// chosen by how well it rebuilds whole poses from these (completion.h), and `eval poses`
// measures completion from them.
//
// File (assets/minimal-poses.json, installed with the program, core/assets.h):
//   {"poses": {"anger": ["4.1", "4.3", "4.5"], "smile_open": ["8.4"], ...}}
// Pose names are those of the synthetic set and the ICT import (synth/pose_recipes.h); FP names
// are MPEG-4 FDP names (pose_data.h). "neutral" has no entry: nothing drawn means neutral.

#include <filesystem>
#include <string>
#include <vector>

namespace facesketch::pose {

struct MinimalPose {
    std::string pose;
    /// FDP names of the observed FPs, at least one, no repeats.
    std::vector<std::string> fps;
};

/// Reads a minimal-pose table. Throws Error naming the file and the key of a malformed entry
/// (not a list of strings, empty, a repeated FP, a name that is not of the form group.point).
/// Entries come out sorted by pose name.
std::vector<MinimalPose> readMinimalPoses(const std::filesystem::path& path);

/// readMinimalPoses(findAsset("minimal-poses.json")).
std::vector<MinimalPose> loadMinimalPoses();

} // namespace facesketch::pose

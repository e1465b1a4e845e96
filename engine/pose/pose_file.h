#pragma once
// The pose model file (`facesketch train-poses -o POSES.model`), in the manner of the face model
// file (stats/model_file.h): versioned binary with a checksum, written atomically.
//
// Layout (little-endian): the 8 bytes "FSKPOSE\0", a u32 format version (kPoseModelVersion), a
// u64 payload length, the payload, then the u64 FNV-1a hash of the payload. The payload holds
// the vertex count and triangles, the FP names and vertices, the pose names, the mean neutral,
// the training FP poses and their pose indices, the minimal table, the completion mixtures
// (primary, alternative) and their scores, and the mapping (FP PPCA, mesh PPCA, joint mixture).
// Matrices are u64 rows, u64 cols, then column-major values; strings are a u64 length and bytes.

#include "pose/pose_model.h"

#include <cstdint>
#include <filesystem>

namespace facesketch::pose {

inline constexpr std::uint32_t kPoseModelVersion = 1;

/// Writes the model atomically (core/atomic_file.h). Throws Error naming the path.
void savePoseModel(const PoseModel& model, const std::filesystem::path& path);

/// Reads a model written by savePoseModel and prepares its mapping. Throws Error naming the path
/// and what is wrong: not a pose model, another version, truncated, checksum mismatch, or
/// inconsistent sizes.
PoseModel loadPoseModel(const std::filesystem::path& path);

} // namespace facesketch::pose

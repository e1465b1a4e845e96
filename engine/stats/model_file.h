#pragma once
// The face model file (`facesketch train -o MODEL`): versioned binary with a checksum, read in
// one pass with no parsing beyond lengths.
//
// Layout (little-endian): the 8 bytes "FSKFACE\0", a u32 format version (kFaceModelVersion),
// a u64 payload length, the payload, then the u64 FNV-1a hash of the payload. The payload
// holds the triangles, the mean face, the segmentation (core labels, member lists, blend
// weights), every segment's mixture (priors; per component mu, W, sigma^2) and clean-up PPCA,
// the correlation mixture, and (since version 2) the head layout: vertex count, skin offset,
// head triangles, and per rigid part its name (u64 length, bytes), vertices, mean positions,
// anchors and a u8 scale flag. Version 1 files (no head) are rejected. Matrices are u64 rows, u64 cols, then column-major values
// (f64, or i32 for the triangles). Storing W instead of covariances keeps a model at 6,000
// vertices in megabytes where the thesis' took 667 MB.

#include "stats/face_model.h"

#include <cstdint>
#include <filesystem>

namespace facesketch::stats {

inline constexpr std::uint32_t kFaceModelVersion = 2;

/// Writes the model to path atomically (core/atomic_file.h). Throws Error naming the path.
void saveFaceModel(const FaceModel& model, const std::filesystem::path& path);

/// Reads a model written by saveFaceModel. Throws Error naming the path and what is wrong: not
/// a model file, an unsupported version, a truncated file, a checksum mismatch, or
/// inconsistent contents.
FaceModel loadFaceModel(const std::filesystem::path& path);

} // namespace facesketch::stats

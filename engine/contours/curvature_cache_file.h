#pragma once
// The curvature cache file itself (contours/curvature_cache.h has the layout): its bytes for a
// batch, and reading one back. No GPU here, so the fuzz target (tests/fuzz/) links it alone.

#include "contours/curvature_gpu.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace facesketch {

/// The file format version (also hashed into the key).
inline constexpr std::uint32_t kCurvatureCacheVersion = 1;

/// The whole file's bytes for a batch of `meshes` meshes of `vertices` vertices with this key.
std::string encodeCurvatureCache(std::uint64_t key, std::uint64_t meshes, std::uint64_t vertices, const GpuCurvature::PackedShapes& p);

/// Reads `file` as the cache of the batch (key, meshes, vertices). True, with `packed` filled,
/// if it is a whole, matching file; otherwise false and `why` says what is wrong (not a cache
/// file, another version, made for other data, truncated, checksum mismatch, unreadable). The
/// file's size is checked against the batch's before it is read, so a huge file in the cache
/// folder costs nothing. meshes * vertices must be the size of a real batch (on the GPU).
bool readCurvatureCacheFile(const std::filesystem::path& file, std::uint64_t key, std::uint64_t meshes, std::uint64_t vertices,
    GpuCurvature::PackedShapes& packed, std::string& why);

} // namespace facesketch

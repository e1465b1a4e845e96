#pragma once
// A file cache of the one-time curvature pass, as the thesis kept curvature files (4.3.4): the
// packed shapes the contour kernels read (contours/curvature_gpu.h), keyed by everything they
// depend on, so that the next run on the same faces reads them instead of computing them (at
// 6,000 vertices x 230 faces: 24 MB, read in tens of milliseconds instead of a second).
//
// File `<key: 16 hex digits>.curv` (little-endian): the 8 bytes "FSKCURV\0", u32 version, u64
// key, u64 meshes, u64 vertices, the shape words (4 per (mesh, vertex)) and the C23 words (1 per
// (mesh, vertex)) as u32 in the GPU's batch layout, then the u64 FNV-1a of all bytes before it.
// The key hashes the triangles, the positions as uploaded (floats) and the SPIR-V of the three
// curvature kernels, so neither other faces nor a changed kernel can read a stale file.

#include "contours/curvature_gpu.h"

#include <filesystem>
#include <string>
#include <vector>

namespace facesketch {

/// $FACESKETCH_CACHE_DIR, else $XDG_CACHE_HOME/facesketch, else $HOME/.cache/facesketch;
/// empty (no caching) if none is set.
std::filesystem::path defaultCacheFolder();

/// The key of a batch (see above).
std::uint64_t curvatureCacheKey(const Triangles& F, const std::vector<float>& positions);

struct CachedCurvature {
    bool restored = false;      ///< read from the file instead of computed
    double milliseconds = 0;    ///< GPU time of the pass, or wall time of the read
    std::filesystem::path file; ///< the cache file used or written (empty: no caching)
    /// Why the file was not used or not written (corrupt, truncated, unwritable), or empty. The
    /// pass itself still succeeded: a cache never stops the work.
    std::string note;
};

/// After curvature.setPositions(positions) for the meshes of triangle list F: restores the
/// packed shapes from `folder` if a whole, matching file is there, else runs the pass and writes
/// the file atomically (core/atomic_file.h). A file that is unreadable, truncated, corrupt or
/// for other data is recomputed and replaced, never trusted. An empty folder just runs the pass.
/// After a restore only the packed shapes are on the GPU (what GpuCandidates reads).
CachedCurvature runCurvatureCached(
    GpuCurvature& curvature, const Triangles& F, const std::vector<float>& positions, const std::filesystem::path& folder);

} // namespace facesketch

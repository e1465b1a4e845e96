#pragma once
// The fuzz targets' entry points: each feeds arbitrary bytes to one reader of outside bytes,
// through the same function the program calls (the bytes are written to a scratch file, since
// every reader takes a path). Shared by the libFuzzer binaries (FACESKETCH_FUZZ=ON, fuzz_main.cpp)
// and the replay test of the normal build (replay.cpp), which runs every file of
// tests/fuzz/<target>/ (seeds and the inputs of every crash found, kept as regress-*) through them.
//
// A target returns normally when the reader accepted the bytes or refused them with
// facesketch::Error; anything else (another exception, a sanitizer report, an allocation above
// libFuzzer's limit, a hang) is a bug.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace facesketch::fuzz {

struct Target {
    const char* name;
    /// True if the reader accepted the bytes, false if it refused them with Error.
    bool (*run)(const std::uint8_t* data, std::size_t size);
};

/// Every target, in a fixed order: obj, obj_vertices, ply, manifest, ict_json, model,
/// curvature_cache, png, session, pose_model (pose/pose_file.h), feature_points (a scan's
/// .points.json, registration/feature_points.h, read and validated).
const std::vector<Target>& targets();

/// The target called `name`; throws std::invalid_argument if there is none.
const Target& target(const std::string& name);

} // namespace facesketch::fuzz

#pragma once
// `facesketch synth`: writes a standardised dataset of synthetic faces (face_generator.h) in the
// dataset format (docs/dataset-format.md). Deterministic: the same options give byte-identical
// files, whatever the number of threads.

#include "dataset/manifest.h"
#include "dataset/synth/face_generator.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace facesketch::dataset {

struct SynthOptions {
    int identities = 250; ///< thesis 3.1: 182 train + 48 contour (+ 20 test)
    Resolution resolution = Resolution::Low;
    std::uint64_t seed = 1;
    bool poses = false;      ///< write the 36 poses (pose_recipes.h) of each posed identity
    int poseIdentities = -1; ///< how many identities get poses (-1: all)
    int threads = 0;         ///< 0: one per hardware thread
};

/// The manifest of a synthetic dataset (topology, labels, samples "face_0000"... in
/// "faces/", poses in "poses/<sample>/<pose>.ply") without writing anything.
Manifest synthManifest(const FaceTopology& topology, const SynthOptions& options);

/// Generates every mesh and writes the dataset folder atomically (dataset.h writeDataset).
/// `progress`, if set, is called with (meshes done, meshes total) from the calling thread.
/// Throws Error for bad options or if the folder cannot be written.
void writeSynthDataset(
    const std::filesystem::path& folder, const SynthOptions& options, const std::function<void(int, int)>& progress = {});

} // namespace facesketch::dataset

#pragma once
// A dataset folder on disk: manifest.json plus one binary PLY per sample and per pose
// (docs/dataset-format.md). Opening validates the manifest and that every listed file exists;
// loading a mesh checks it has the manifest's vertex count and topology, so every later stage
// can rely on one shared vertex structure (thesis 3.1).

#include "dataset/manifest.h"

#include <Eigen/Core>
#include <filesystem>
#include <functional>

namespace facesketch::dataset {

struct Dataset {
    std::filesystem::path folder;
    Manifest manifest;
};

/// Reads folder/manifest.json and checks that every sample and pose file exists.
/// Throws Error naming the file and field.
Dataset openDataset(const std::filesystem::path& folder);

/// Reads one mesh of the dataset (`file` relative to the folder) and checks that its vertex
/// count and triangles equal the manifest's. Throws Error naming the file.
Mesh loadMesh(const Dataset& dataset, const std::filesystem::path& file);

/// The neutral meshes of every sample with `role`, one row per sample in manifest order:
/// #samples by 3*#V, row i = (x0, y0, z0, x1, y1, z1, ...) of sample i, in the dataset's units.
/// `component`, if not empty, keeps only that component's vertices (e.g. "skin").
Eigen::MatrixXd loadShapes(const Dataset& dataset, Role role, const std::string& component = "");

/// Flattens a mesh's vertices into one row (x0, y0, z0, x1, ...), the layout of loadShapes.
Eigen::RowVectorXd flatten(const Vertices& V);
/// Inverse of flatten: 3*#V values back to #V by 3.
Vertices unflatten(const Eigen::Ref<const Eigen::RowVectorXd>& row);

/// Writes a dataset folder atomically: `fill(tmp)` writes the meshes into an empty temporary
/// sibling folder `.NAME.tmp-*`, then the manifest is validated and written there, every listed
/// file is checked to exist, everything is flushed to disk (core/atomic_file.h StagingFolder),
/// and the temporary folder is swapped with `folder` in one atomic step (renameat2
/// RENAME_EXCHANGE) before the old one is deleted. So at every moment, even if the process is
/// killed, `folder` is a complete dataset: the whole old one or the whole new one, where
/// complete means manifest.json and every sample and pose file it lists, all fully written
/// (tests/cli/kill_during_save.sh). A kill may leave a `.NAME.tmp-*` folder beside it,
/// never read. An existing `folder` is replaced only if it is empty or holds a manifest.json
/// (i.e. it is a dataset); on any failure the temporary folder is removed and `folder` is
/// untouched.
void writeDataset(
    const std::filesystem::path& folder, const Manifest& manifest, const std::function<void(const std::filesystem::path& tmp)>& fill);

} // namespace facesketch::dataset

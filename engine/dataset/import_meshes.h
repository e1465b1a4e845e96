#pragma once
// `facesketch import meshes DIR`: a folder of meshes that share one topology (already in
// correspondence, e.g. exported from a morphable model or a registration tool) becomes a
// standardised dataset (thesis 3.1).
//
// Input. Every *.obj and *.ply file directly inside DIR (extension case-insensitive), taken in
// byte order of their file names, is one identity in its neutral pose. All must have the same
// vertex count and the same triangles (after fan triangulation of polygons) as the first;
// the first difference stops the import with an Error naming both files and the triangle.
// Sample names are the file stems ("alice.obj" -> "alice"), written as "faces/<stem>.ply".
//
// Labels, optional: DIR/landmarks.json (or the file given as `labels`), one JSON object
//   {
//     "units": "cm",                       // units of the meshes: mm (default), cm or m
//     "landmarks": {"prn": 4841, ...},     // name -> 0-based vertex (docs/dataset-format.md)
//     "mpeg4": {"9.3": 4841, ...},         // FDP name -> vertex
//     "contours": {"eyebrow_l": [1, 2, 3]},// name -> ordered vertex path
//     "components": {"skin": [0, 9409], "eye_left": [9409, 10979]},  // default: all skin
//     "excluded": [17, 18]                 // never contour candidates
//   }
// Every key is optional. Meshes are converted to mm. The labels are validated like a manifest
// (errors name the labels file and the field).
//
// Roles. The samples are shuffled by Random(seed).permutation (core/random.h: Fisher-Yates on
// std::mt19937_64(seed), the same order with every standard library) and the
// shuffled order gets the roles of manifest.h splitRoles: the thesis' 182 : 48 : 20 split of 250
// scaled to the count, train first, then contour, then test. The manifest lists samples in
// file-name order.

#include "dataset/manifest.h"

#include <cstdint>
#include <filesystem>

namespace facesketch::dataset {

struct MeshImportOptions {
    std::uint64_t seed = 1;       ///< role shuffle
    int vertices = 0;             ///< > 0: simplify to about this many vertices (simplify.h)
    std::filesystem::path labels; ///< labels file; empty: DIR/landmarks.json if it exists
};

/// Roles for `count` samples in file order: splitRoles(count) dealt out by the seeded shuffle.
std::vector<Role> shuffledRoles(int count, std::uint64_t seed);

/// Reads the folder (see above) and writes the dataset folder `output` atomically
/// (dataset.h writeDataset): nothing is written if any mesh or the labels are bad.
/// Returns the manifest written. Throws Error naming the file (and line, for text formats).
Manifest importMeshes(const std::filesystem::path& folder, const std::filesystem::path& output, const MeshImportOptions& options = {});

} // namespace facesketch::dataset

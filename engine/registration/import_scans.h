#pragma once
// `facesketch import scans DIR --template DATASET -o NEW` (issue 15): every scan in a folder
// registered into a template dataset's topology (registration/register.h), written as a new
// standardised dataset with the template's labels.
//
// Input. Every *.obj and *.ply directly inside DIR (extension case-insensitive), in byte order of
// their file names, with its feature points in DIR/<stem>.points.json (feature_points.h); the
// scans' units are `units`. Sample names are the stems, written as "faces/<stem>.ply".
//
// The template is the mean of the dataset's training faces (meanFace) with its landmarks; its
// `skin` component is registered and its other components follow the RBF approximation.
//
// Output. The template's manifest (units, axes, topology, components, landmarks, MPEG-4 points,
// contours, excluded vertices) with the registered scans as samples and no poses; roles as every
// importer deals them (dataset/import_meshes.h shuffledRoles: the thesis' 182 : 48 : 20 split,
// shuffled by `seed`). A scan that fails (no points file, bad points, a bad mesh) is reported with
// its reason and left out; the others are imported. Written atomically (dataset.h writeDataset);
// nothing is written if no scan registers.

#include "dataset/dataset.h"
#include "registration/register.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace facesketch::registration {

/// The mean of a dataset's training faces in its topology and units. Throws Error if it has none.
Mesh meanFace(const dataset::Dataset& dataset);

struct ScanImportOptions {
    std::uint64_t seed = 1;   ///< role shuffle
    std::string units = "mm"; ///< units of the scans and their points
    RegistrationOptions registration;
    /// Threads registering scans (0: one per hardware thread); the dataset written is the same
    /// for any number.
    int threads = 0;
    /// Called from the calling thread after each scan it registered: (scans done by all
    /// threads, scan count, that scan's file name). With one thread, after every scan in order.
    std::function<void(int, int, const std::string&)> progress;
};

struct ScanFailure {
    std::filesystem::path scan;
    std::string reason; ///< the Error's message
};

struct ScanImport {
    dataset::Manifest manifest;        ///< as written
    std::vector<ScanFailure> failures; ///< scans left out, in file order
};

/// Registers every scan of `folder` onto `templ` and writes the dataset `output` (see above).
/// Throws Error if the folder holds no scan, an option is bad, or no scan registers (the message
/// lists each failure).
ScanImport importScans(const std::filesystem::path& folder, const dataset::Dataset& templ, const std::filesystem::path& output,
    const ScanImportOptions& options = {});

} // namespace facesketch::registration

#pragma once
// Feature regions of a face for `facesketch eval observe --region NAME` and the observation
// tests: the skin vertices measured when a user draws only one part of the face.
//
// Names and definitions (all in the face model's skin numbering, on the model's mean face):
//   nose        within `radius` mm of prn, al, sbal, sn, cs1 and the nostril contours
//   mouth       within `radius` mm of ls, li, sto, ch, cph and the four lip contours
//   chin        within `radius` mm of pg, gn, sl
//   eyes        within `radius` mm of en, ex, ps, pi and the eye_socket contours
//   brows       within `radius` mm of os, mf, g and the eyebrow contours
//   mouth_chin  mouth and chin together;  eyes_brows  eyes and brows together
//   segment:N   the core vertices of the model's segment N (1-based, as `facesketch train` lists them)
// Landmarks and contours the manifest lacks are skipped (names as docs/dataset-format.md,
// _l and _r for both sides).

#include "dataset/manifest.h"
#include "stats/face_model.h"

#include <string>
#include <vector>

namespace facesketch::model {

/// The landmark-based region names above (without the segment:N form).
std::vector<std::string> featureRegionNames();

/// The region's skin vertices in ascending order. Throws Error naming the region for an
/// unknown name, a segment out of range, or a region with no landmark in the manifest.
std::vector<int> featureRegion(
    const dataset::Manifest& manifest, const stats::FaceModel& model, const std::string& name, double radius = 10.0);

} // namespace facesketch::model

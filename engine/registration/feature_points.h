#pragma once
// Feature points (FPs) of a scan for registration (thesis 3.2.6-3.2.7): named craniofacial
// landmarks with the names of docs/dataset-format.md (thesis Table 3.1), read from a JSON file
// {"prn": [x, y, z], "en_l": [x, y, z], ...} in the scan's own coordinates and units.
//
// Required and optional points (thesis 3.2.7). The fit needs the points that fix the face's
// position, orientation and proportions, and those lining the main features:
//   required: prn, sn, en_l, en_r, ex_l, ex_r, ch_l, ch_r, pg.
// Every other landmark of the table improves the fit where it lies (g, n, s, cs1, al_*, sbal_*,
// ps_*, pi_*, os_*, mf_*, ls, sto, li, cph_*, sl, gn, obs_*). The thesis found g, s, c' and sl
// can be left out with a negligible effect after registration (fig. 3.9).
//
// Missing points (thesis 3.2.6, where v and op were placed from the generic head because its
// scans were face masks): a point the template has but the scan lacks (typically the ears,
// obs_l/obs_r) is estimated by moving the template's point with the least-squares similarity
// (geometry/similarity.h) that takes the template's other points onto the scan's.

#include "core/mesh.h"

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace facesketch::registration {

class SurfaceQuery;

/// name -> position, in the scan's coordinates.
using FeaturePoints = std::map<std::string, Eigen::Vector3d>;

/// Every landmark name of docs/dataset-format.md, in table order.
const std::vector<std::string>& landmarkNames();
/// The points registration requires (above).
const std::vector<std::string>& requiredFeaturePoints();

/// Reads {name: [x, y, z]}. Throws Error naming the file and the key if the document is not an
/// object, a value is not 3 finite numbers, or a name is not a landmark name.
FeaturePoints readFeaturePoints(const std::filesystem::path& path);

/// What validateFeaturePoints accepts.
struct FeaturePointLimits {
    /// Largest distance of a point from the scan's surface, in scan units (mm).
    double maxDistanceFromSurface = 3.0;
    /// Two points closer than this (scan units) are the same point placed twice.
    double minSeparation = 0.5;
};

/// Checks a scan's points before registration and throws Error "<scanName>: ..." naming the
/// point at fault: a required point missing, a non-finite coordinate, two points at the same
/// place, all points on one line or one plane (the affine part of the RBF is then undetermined),
/// or a point farther than limits.maxDistanceFromSurface from the scan's surface.
void validateFeaturePoints(
    const FeaturePoints& points, const SurfaceQuery& scan, const std::string& scanName, const FeaturePointLimits& limits = {});

/// The scan's points completed from the template's (thesis 3.2.6).
struct CompletedPoints {
    std::vector<std::string> names;     ///< every point the template has, sorted
    Vertices templatePoints;            ///< #names by 3, on the template
    Vertices scanPoints;                ///< #names by 3, on the scan (given or estimated)
    std::vector<std::string> estimated; ///< names the scan lacked, estimated from the template
    std::vector<std::string> unused;    ///< names the scan has but the template does not
};

/// Pairs the template's landmarks (name -> position on the template) with the scan's points and
/// estimates the missing ones by the similarity fitted on the shared ones. Throws Error naming
/// `scanName` if fewer than 4 names are shared.
CompletedPoints completeFeaturePoints(const FeaturePoints& templatePoints, const FeaturePoints& scanPoints, const std::string& scanName);

} // namespace facesketch::registration

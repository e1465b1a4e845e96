#pragma once
// Candidates per stroke point (thesis 4.4, 4.8.5.2). The cloud is the contour candidates of
// every candidate face inside the stroke's box (GpuCandidates::build with the box as
// ContourParams::rect and a world sphere around the projected stroke); each point then gets the
// candidates within a screen radius scaled by tau and within a depth tolerance of its projected
// depth along the view axis, at most `maxPerPoint` of them, nearest first.
//
// Cost: O(M) to index a cloud of M candidates; per point O(candidates in its radius x log).

#include "contours/candidates.h"
#include "geometry/camera.h"

#include <Eigen/Core>
#include <vector>

namespace facesketch::sketch {

/// Pixels per mm at world point `at`, for a length parallel to the view plane.
double pixelsPerMm(const Camera& camera, const Eigen::Vector3d& at);

/// The x and y rows (view plane) and the third row (view axis, towards the camera) of the
/// camera's rotation.
Eigen::Matrix<double, 2, 3> viewPlaneRows(const Camera& camera);
Eigen::Vector3d viewAxis(const Camera& camera);

/// `base` with its rect set to the box of the on-screen points (inside the viewport widened by
/// `radiusPx`) widened by radiusPx, and its sphere around the world points of those points,
/// widened by `worldMarginMm`. Returns false (and leaves base's culling alone) if no point is
/// within radiusPx of the viewport.
bool strokeBox(ContourParams& base, const Camera& camera, const std::vector<Eigen::Vector2d>& screen,
    const std::vector<Eigen::Vector3d>& world, double radiusPx, double worldMarginMm);

/// Per point: indices into `cloud` of the candidates within radiusPx on screen and
/// depthToleranceMm of the point along the view axis, nearest on screen first (ties: lower
/// index), at most maxPerPoint.
std::vector<std::vector<int>> candidatesPerPoint(const std::vector<Candidate>& cloud, const Camera& camera,
    const std::vector<Eigen::Vector2d>& screen, const std::vector<Eigen::Vector3d>& world, double radiusPx, double depthToleranceMm,
    int maxPerPoint);

} // namespace facesketch::sketch

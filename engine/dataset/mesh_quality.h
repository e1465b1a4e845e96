#pragma once
// Quality checks for meshes of a standardised set: degenerate triangles, folds, triangles that
// flipped relative to a reference shape of the same topology, and self-intersections.
// Used by the generator's tests and by importers to reject broken input.

#include "core/mesh.h"

#include <utility>
#include <vector>

namespace facesketch::dataset {

/// Triangles whose area is below minArea (mm^2) or whose smallest angle is below minAngleDeg.
std::vector<int> degenerateTriangles(const Mesh& mesh, double minArea = 1e-4, double minAngleDeg = 0.5);

/// Triangles whose normal points more than 90 degrees away from the same triangle's normal on
/// `reference` (#V by 3, same topology), i.e. that turned inside out relative to it.
std::vector<int> flippedTriangles(const Mesh& mesh, const Vertices& reference);

/// Of `triangles` (indices into mesh.F), those whose normal points towards `centre`, i.e. that
/// face inwards on a surface that is star-shaped about `centre` (a closed convex-ish part, or
/// the synthetic skin about the origin).
std::vector<int> trianglesFacingCentre(const Mesh& mesh, const Eigen::Vector3d& centre, const std::vector<int>& triangles);

/// Pairs of triangles sharing an edge whose normals differ by more than maxAngleDeg: folds
/// where the surface doubles back on itself.
std::vector<std::pair<int, int>> foldedEdges(const Mesh& mesh, double maxAngleDeg = 150);

/// Pairs (i < j) of triangles that share no vertex and intersect (one's edge pierces the other).
/// Uses a uniform grid of about the mean edge length, so it runs in near-linear time.
std::vector<std::pair<int, int>> selfIntersections(const Mesh& mesh);

/// True if segment p-q crosses triangle (a, b, c) (Moller-Trumbore); an endpoint or edge
/// touching counts as crossing, a segment parallel to the triangle's plane does not.
bool segmentHitsTriangle(
    const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// True if triangles (a0, a1, a2) and (b0, b1, b2) intersect (an edge of one crosses the
/// other). Coplanar overlaps are not reported.
bool trianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2, const Eigen::Vector3d& b0,
    const Eigen::Vector3d& b1, const Eigen::Vector3d& b2);

} // namespace facesketch::dataset

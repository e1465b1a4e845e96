#pragma once
// Closest points on a triangle mesh, for the registration of scans (thesis 3.2.10-3.2.12):
// checking that feature points lie on the scan, and measuring how far a registered face is from
// the scan's surface (the error maps of thesis figs. 3.13-3.14).
//
// A uniform grid over the mesh's bounding box holds every triangle in each cell its bounding box
// overlaps; a query visits rings of cells around the query's cell until no unvisited cell can be
// nearer than the best triangle found. The point-triangle distance follows the Voronoi-region
// case analysis of Ericson, "Real-Time Collision Detection" (2005), 5.1.5.

#include "core/mesh.h"

#include <Eigen/Core>
#include <vector>

namespace facesketch::registration {

struct ClosestPoint {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();       ///< the nearest point of the surface
    double distance = 0.0;                                 ///< |query - point|, mesh units (mm)
    int triangle = -1;                                     ///< the triangle holding `point`
    Eigen::Vector3d barycentric = Eigen::Vector3d::Zero(); ///< of `point` over `triangle`'s corners (sum 1)
    /// True if `point` lies on a boundary edge or boundary vertex of the mesh (an edge with one
    /// triangle): the query is then beside the surface rather than over it, e.g. over a hole or
    /// outside a face mask.
    bool onBoundary = false;
};

/// Closest-point queries on one triangle mesh. The mesh is copied; construction is O(#F).
class SurfaceQuery {
public:
    /// @param[in] mesh  a mesh with at least one triangle (throws Error otherwise).
    explicit SurfaceQuery(const Mesh& mesh);

    /// The point of the mesh's surface nearest to `p`.
    ClosestPoint closest(const Eigen::Vector3d& p) const;

    const Mesh& mesh() const { return mesh_; }

private:
    Mesh mesh_;
    Eigen::Vector3d lower_, cellSize_;
    Eigen::Vector3i cells_;
    std::vector<int> cellStart_, cellTriangles_; // CSR lists of the triangles of each cell
    std::vector<char> boundaryEdge_;             // 3 per triangle: edge (i, i+1) has one triangle
    std::vector<char> boundaryVertex_;
    mutable std::vector<unsigned> stamp_;
    mutable unsigned query_ = 0;
};

/// The point of triangle (a, b, c) nearest to p, with its barycentric coordinates (sum 1).
Eigen::Vector3d closestPointOnTriangle(
    const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Vector3d& barycentric);

} // namespace facesketch::registration

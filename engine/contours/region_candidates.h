#pragma once
// The contour candidates of one mesh inside a screen rectangle and world sphere, from the
// curvature of the part of the mesh around them only (on the CPU, in double): what a stroke
// reads of the face it is drawn on (sketch/mapper.h, the current face's own contours), where
// the whole face's curvature on lavapipe cost 27 ms a reading at 22,858 vertices for a box
// that covers a fraction of it.
//
// The candidates equal contourCandidates() on the whole mesh and its estimateCurvature(), bit
// for bit: a vertex's derivative of curvature reads its one-ring's curvature, which reads the
// normals of the two-ring, which read every triangle at those vertices; the region keeps every
// triangle touching a vertex within two rings of the rectangle's vertices (three with rtsc's
// filter, which reads the one-ring's derivative too), in F's order (the
// vertex frames start from a vertex's first triangle in F), and numbers its vertices in
// ascending order (the suggestive test breaks ties by the lower index).
//
//   RegionCandidates own(F, vertexCount, flags);        // once per topology
//   std::vector<Candidate> c = own.build(face, camera, params);

#include "contours/candidates.h"
#include "geometry/wedges.h"

#include <cstdint>
#include <vector>

namespace facesketch {

class RegionCandidates {
public:
    /// F: the topology (validated); flags: #V VertexFlag bits, or empty. Throws Error for
    /// flags of the wrong size.
    RegionCandidates(const Triangles& F, Eigen::Index vertexCount, std::vector<std::uint32_t> flags);

    /// The candidates of `mesh` (on the topology; validated) seen by `camera` inside
    /// params.rect and params.sphere, sorted by vertex, mesh index 0. Throws Error for a mesh
    /// of another topology.
    std::vector<Candidate> build(const Mesh& mesh, const Camera& camera, const ContourParams& params);

    /// Vertices and triangles of the region the last build() took the curvature of.
    Eigen::Index lastRegionVertices() const { return lastVertices_; }
    Eigen::Index lastRegionTriangles() const { return lastTriangles_; }

private:
    Triangles F_;
    Eigen::Index vertexCount_;
    std::vector<std::uint32_t> flags_;
    Neighbours rings_;
    std::vector<std::uint32_t> faceOffsets_, faces_; // triangles at each vertex, ascending
    Eigen::Index lastVertices_ = 0, lastTriangles_ = 0;
};

} // namespace facesketch

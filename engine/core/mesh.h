#pragma once
// The triangle mesh every module passes around. Units are millimetres unless a dataset says
// otherwise; the face looks down +z with +y up (docs/dataset-format.md). Triangles are
// counter-clockwise seen from outside, so cross(b - a, c - a) points outward.

#include <Eigen/Core>
#include <Eigen/Geometry> // cross products on rows of Vertices
#include <cstdint>

namespace facesketch {

/// #V by 3 vertex positions, one row per vertex. Row-major so rows are contiguous xyz.
using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F by 3 vertex indices into Vertices, one row per triangle.
using Triangles = Eigen::Matrix<std::int32_t, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct Mesh {
    Vertices V;
    Triangles F;

    Eigen::Index vertexCount() const { return V.rows(); }
    Eigen::Index triangleCount() const { return F.rows(); }
};

/// Throws Error naming `what` and the first offending vertex or triangle if V holds a NaN or
/// infinity, or F an index outside [0, #V) or a triangle that repeats a vertex.
void validateMesh(const Mesh& mesh, const std::string& what);

} // namespace facesketch

#pragma once
// The triangle mesh every module passes around. Units are millimetres unless a dataset says
// otherwise; the face looks down +z with +y up (docs/dataset-format.md). Triangles are
// counter-clockwise seen from outside, so cross(b - a, c - a) points outward.
//
// One face has four layouts, and this file holds the views between the first three:
// - `Vertices`, #V by 3 doubles, one row per vertex;
// - a 3#V vector (x0, y0, z0, x1, ...), what the statistics work on: asVector / asVertices;
// - mesh-major floats, many meshes of one topology in one array (mesh, then vertex, then xyz),
//   what the GPU kernels are fed: meshInBatch views one mesh of it as #V by 3 floats;
// - the GPU's batch layout (vertex-major vec4s, shaders/shared.h), converted to and from
//   mesh-major by geometry/mesh_batch.h.
// Vertices is row-major, so the first three are the same bytes in the same order and the views
// copy nothing. A view aliases its argument: keep that alive (and unresized) while using it.

#include <Eigen/Core>
#include <Eigen/Geometry> // cross products on rows of Vertices
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace facesketch {

/// #V by 3 vertex positions, one row per vertex. Row-major so rows are contiguous xyz.
using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F by 3 vertex indices into Vertices, one row per triangle.
using Triangles = Eigen::Matrix<std::int32_t, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// #V by 3 single-precision positions: one mesh of a mesh-major float array.
using VerticesF = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// V's 3#V coordinates as one vector (x0, y0, z0, x1, ...), without a copy.
Eigen::Map<Eigen::VectorXd> asVector(Vertices& V);
Eigen::Map<const Eigen::VectorXd> asVector(const Vertices& V);
/// A vector of 3#V coordinates as #V by 3 vertices, without a copy; throws Error if its size
/// is not a multiple of 3.
Eigen::Map<Vertices> asVertices(Eigen::VectorXd& x);
Eigen::Map<const Vertices> asVertices(const Eigen::VectorXd& x);
/// Mesh `mesh` of a mesh-major float array of meshes of `vertexCount` vertices, as #V by 3
/// floats, without a copy; throws Error if the array holds no such mesh.
Eigen::Map<VerticesF> meshInBatch(std::vector<float>& meshMajor, Eigen::Index vertexCount, std::size_t mesh);
Eigen::Map<const VerticesF> meshInBatch(const std::vector<float>& meshMajor, Eigen::Index vertexCount, std::size_t mesh);

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

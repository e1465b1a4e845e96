#pragma once
// Area-weighted vertex normals (each incident triangle weighted by its area, i.e. the sum of
// unnormalised face cross products; Max 1999 compares this and other weightings). The CPU
// reference for shaders/normals.comp.glsl and the normals the renderer uses.

#include "core/mesh.h"

namespace facesketch {

/// #V by 3 unit normals of `mesh`, double precision. A vertex whose incident triangles have
/// zero total area (or no triangles) gets the zero vector. Outward for counter-clockwise
/// triangles seen from outside.
Vertices vertexNormals(const Mesh& mesh);

/// The same for a batch of meshes sharing `F`: `positions` is meshCount * #V * 3 floats
/// (mesh-major, then vertex, then xyz), and so is the result; accumulated in double.
std::vector<float> vertexNormalsBatch(const std::vector<float>& positions, const Triangles& F, Eigen::Index vertexCount);

} // namespace facesketch

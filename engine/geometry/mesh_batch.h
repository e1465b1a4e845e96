#pragma once
// Per-vertex xyz data of many meshes with one topology, in the GPU's "batch layout"
// (shaders/shared.h): vertex v of mesh m as 4 floats (x, y, z, 0) at float index
// 4 * (v * meshCount + m).
// Host code mostly holds mesh-major arrays (mesh, then vertex, then xyz); these functions
// convert between the two.

#include <cstddef>
#include <vector>

namespace facesketch {

/// Mesh-major (meshCount * vertexCount * 3 floats) to batch layout (4 floats per vertex). Throws Error if the size
/// does not match.
std::vector<float> toBatchLayout(const std::vector<float>& meshMajor, std::size_t meshCount, std::size_t vertexCount);
/// Batch layout back to mesh-major.
std::vector<float> fromBatchLayout(const std::vector<float>& batch, std::size_t meshCount, std::size_t vertexCount);

} // namespace facesketch

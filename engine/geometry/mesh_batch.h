#pragma once
// Per-vertex xyz data of many meshes with one topology, in the GPU's "batch layout"
// (shaders/shared.h): vertex v of mesh m as 4 floats (x, y, z, 0) at float index
// 4 * (v * meshCount + m).
// Host code mostly holds mesh-major arrays (mesh, then vertex, then xyz); these functions
// convert between the two.

#include "core/mesh.h"
#include "gpu/buffers.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace facesketch {

/// Mesh-major (meshCount * vertexCount * 3 floats) to batch layout (4 floats per vertex). Throws Error if the size
/// does not match.
std::vector<float> toBatchLayout(const std::vector<float>& meshMajor, std::size_t meshCount, std::size_t vertexCount);
/// Batch layout back to mesh-major, keeping the first `components` (1 to 4) of each vec4: 3 for
/// positions and normals, 4 for per-vertex vec4 results (curvature, its derivative).
std::vector<float> fromBatchLayout(
    const std::vector<float>& batch, std::size_t meshCount, std::size_t vertexCount, std::size_t components = 3);

/// The vertices of `meshes` as one mesh-major float array (mesh, then vertex, then xyz), the
/// input of the batch kernels. Throws Error if the meshes differ in vertex count.
std::vector<float> meshMajorPositions(const std::vector<Mesh>& meshes);

/// Uploads the wedges of F (geometry/wedges.h) that every batch kernel gathers over:
/// `offsets` (#V + 1 uint) and `corners` (3 #F uvec2), new buffers owned by the caller, usable
/// as storage and as texel buffers.
void uploadWedges(gpu::Device& device, const Triangles& F, Eigen::Index vertexCount, gpu::Buffer& offsets, gpu::Buffer& corners);

/// Texel views of the wedge buffers (R32UI offsets, RG32UI corners), which the kernels read as
/// texel buffers (gpu::TexelView); destroy before the buffers.
struct WedgeTexels {
    gpu::TexelView offsets, corners;
};
WedgeTexels createWedgeTexels(gpu::Device& device, const gpu::Buffer& offsets, const gpu::Buffer& corners);
void destroyWedgeTexels(gpu::Device& device, WedgeTexels& texels);

/// The y extent (vertex rows) to dispatch a batch kernel with, meshes along x: one invocation
/// per (mesh, vertex), so `vertexCount`. The kernels do not loop over vertices: on lavapipe a
/// grid-stride loop around the body made the contour kernels twice as slow (BENCHMARKS.md).
/// Throws Error when the rows need more than the 65535 workgroups every device has along y.
std::uint32_t batchRows(std::uint32_t vertexCount, std::uint32_t groupVertices);

} // namespace facesketch

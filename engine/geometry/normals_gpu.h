#pragma once
// Area-weighted vertex normals on the GPU for a batch of meshes that share one triangle list:
// the shape of every dataset kernel (many training faces, one topology). shaders/normals.comp.glsl;
// CPU reference: geometry/normals.h (vertexNormalsBatch).
//
//   GpuNormals normals(device, F, vertexCount);   // uploads the topology once
//   normals.setPositions(positions);               // meshCount * #V * 3 floats
//   normals.run();                                 // dispatch, wait
//   std::vector<float> n = normals.normals();      // same layout as positions

#include "core/mesh.h"
#include "geometry/mesh_batch.h"
#include "gpu/buffers.h"
#include "gpu/compute.h"
#include "gpu/timer.h"

#include <vector>

namespace facesketch {

class GpuNormals {
public:
    GpuNormals(gpu::Device& device, const Triangles& F, Eigen::Index vertexCount);
    ~GpuNormals();
    GpuNormals(const GpuNormals&) = delete;
    GpuNormals& operator=(const GpuNormals&) = delete;

    /// Uploads meshCount meshes (positions.size() / (3 #V)); reallocates only when the batch grows.
    /// Throws Error if the size is not a whole number of meshes or a coordinate is not finite.
    void setPositions(const std::vector<float>& positions);
    /// Records and submits one dispatch over all meshes and waits; returns the GPU time in ms
    /// from timestamps (or -1 without timestamp support).
    double run();
    /// Reads back meshCount * #V * 3 floats.
    std::vector<float> normals();

private:
    gpu::Device& device_;
    Eigen::Index vertexCount_;
    std::uint32_t meshCount_ = 0;
    gpu::ComputeProgram program_;
    gpu::Buffer wedgeOffsets_, wedges_, positions_, normals_;
    WedgeTexels wedgeTexels_;
    gpu::TexelView positionTexels_; // of positions_, which may be larger than the batch (reused)
    gpu::GpuTimer timer_;
};

/// One-off convenience: normals of a batch, with a temporary GpuNormals.
std::vector<float> vertexNormalsGpu(gpu::Device& device, const std::vector<float>& positions, const Triangles& F, Eigen::Index vertexCount);

} // namespace facesketch

#pragma once
// Curvature of every face of a dataset at once on the GPU: Max-weighted normals, principal
// curvatures and directions, and the derivative of curvature (Rusinkiewicz 2004), for a batch
// of meshes sharing one triangle list. The one-time pass of thesis 4.3.4 ("caching curvature
// files"): run once per dataset, its buffers stay on the GPU for every later view.
// CPU reference: contours/curvature.h, same conventions (convex positive, k1 >= k2).
//
//   GpuCurvature curvature(device, F, vertexCount);
//   curvature.setPositions(positions);   // meshCount * #V * 3 floats, mesh-major
//   curvature.run();                      // three dispatches, waits
//   GpuCurvature::Result r = curvature.download();

#include "core/mesh.h"
#include "geometry/mesh_batch.h"
#include "geometry/wedges.h"
#include "gpu/buffers.h"
#include "gpu/compute.h"
#include "gpu/timer.h"

#include <cstdint>
#include <vector>

namespace facesketch {

/// Decoders of the GPU's packed formats (GLSL unpackHalf2x16, unpackSnorm2x16 and the
/// octahedral unit vectors of shaders/octahedral.glsl), for reading packed shapes on the host.
float halfToFloat(std::uint16_t h);
Eigen::Vector3d octDecode(std::uint32_t packedSnorm2x16);

class GpuCurvature {
public:
    GpuCurvature(gpu::Device& device, const Triangles& F, Eigen::Index vertexCount);
    ~GpuCurvature();
    GpuCurvature(const GpuCurvature&) = delete;
    GpuCurvature& operator=(const GpuCurvature&) = delete;

    /// Uploads meshCount meshes; throws Error on a partial mesh or a non-finite coordinate.
    void setPositions(const std::vector<float>& positions);
    /// Normals, curvature and its derivative for every mesh; returns GPU milliseconds (or -1).
    double run();
    /// Whether the packed shapes belong to the current positions: run() or uploadShapes() has
    /// been called since setPositions().
    bool hasShapes() const { return hasShapes_; }
    /// Numbers that change whenever setPositions() changes the positions, and whenever
    /// setPositions(), run() or uploadShapes() changes the packed shapes, so that data derived
    /// from them (contours/culling_gpu.h) knows when it is stale.
    std::uint64_t positionsVersion() const { return positionsVersion_; }
    std::uint64_t shapesVersion() const { return shapesVersion_; }

    /// Host copies, mesh-major: element (mesh m, vertex v) at m * #V + v.
    struct Result {
        std::vector<float> normal;     ///< xyz per vertex
        std::vector<float> curvature;  ///< k1, k2, area, 0 per vertex
        std::vector<float> direction;  ///< dir1 xyz per vertex (dir2 = normal x dir1)
        std::vector<float> derivative; ///< C111, C112, C122, C222 per vertex
        /// The packed shape the contour tests read (shaders/shared.h), decoded: normal xyz,
        /// dir1 xyz, k1 k2, C111..C222 per vertex (3 + 3 + 2 + 4 floats); zeros where the
        /// vertex has no tangent plane. Octahedral snorm16 vectors and half-float curvatures.
        std::vector<float> packed;
    };
    Result download();

    /// The packed shapes the contour kernels read (shaders/shared.h), exactly as on the GPU in
    /// batch layout: 4 words per (mesh, vertex) and 1 of SHAPE_C23. For caching the one-time
    /// pass (contours/curvature_cache.h), as the thesis kept curvature files (4.3.4).
    struct PackedShapes {
        std::vector<std::uint32_t> shapes;
        std::vector<std::uint32_t> c23;
    };
    PackedShapes downloadShapes();
    /// Restores shapes of the current positions instead of run(). Only the packed shapes are
    /// then valid: download() throws until run() is called. Throws Error on a size mismatch.
    void uploadShapes(const PackedShapes& packed);

    std::uint32_t meshCount() const { return meshCount_; }
    Eigen::Index vertexCount() const { return vertexCount_; }

    // For kernels that consume the results (contour tests): batch layout, see shaders/shared.h.
    const gpu::Buffer& positions() const { return positions_; }
    const gpu::Buffer& normals() const { return normals_; }
    const gpu::Buffer& curvatures() const { return curvature_; }
    const gpu::Buffer& directions() const { return directions_; }
    const gpu::Buffer& derivatives() const { return derivatives_; }
    const gpu::Buffer& shapes() const { return shapes_; }
    const gpu::Buffer& shapesC23() const { return shapesC23_; }
    const gpu::Buffer& wedgeOffsets() const { return wedgeOffsets_; }
    /// Texel views of positions (RGBA32F), shapes (RGBA32UI) and SHAPE_C23 (R32UI), same layout.
    const gpu::TexelView& positionTexels() const { return positionTexels_; }
    const gpu::TexelView& shapeTexels() const { return shapeTexels_; }
    const gpu::TexelView& c23Texels() const { return c23Texels_; }
    /// The wedges on the host (geometry/wedges.h), for kernels that need other views of the topology.
    const Wedges& hostWedges() const { return hostWedges_; }
    const gpu::Buffer& wedges() const { return wedges_; }

private:
    void destroyBatchBuffers();

    gpu::Device& device_;
    Eigen::Index vertexCount_;
    std::uint32_t meshCount_ = 0;
    bool shapesOnly_ = false; // restored by uploadShapes: the other result buffers are stale
    bool hasShapes_ = false;
    std::uint64_t positionsVersion_ = 0, shapesVersion_ = 0;
    gpu::ComputeProgram normalsProgram_, curvatureProgram_, derivativeProgram_;
    Wedges hostWedges_;

    gpu::Buffer wedgeOffsets_, wedges_;
    WedgeTexels wedgeTexels_;
    gpu::Buffer positions_, normals_, curvature_, directions_, derivatives_, shapes_, shapesC23_;
    gpu::TexelView positionTexels_, normalTexels_, curvatureTexels_, directionTexels_, shapeTexels_, c23Texels_;
    gpu::GpuTimer timer_;
};

} // namespace facesketch

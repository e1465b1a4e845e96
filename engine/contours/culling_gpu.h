#pragma once
// What lets a view of the candidate cloud (contours/candidates_gpu.h) skip work, derived from a
// GpuCurvature's batch: per vertex a bounding sphere over every mesh (the vertices no mesh
// shows in a view's rectangle and sphere are not visited) and a normal cone (nor those that
// face away in every mesh), and per (mesh, vertex) a sign lock (pairs whose one-ring keeps one
// sign of k_r for any view skip the zero-crossing test, which they cannot pass).
// Computed on the host from the curvature's positions and packed shapes, read back from the GPU;
// the sign locks go back up as a texel buffer for pass 1.
//
//   GpuCulling culling(device, curvature);  // after curvature.run() or uploadShapes()
//   culling.update(curvature);              // recomputes only if the curvature changed since

#include "contours/curvature_gpu.h"
#include "geometry/wedges.h"
#include "gpu/buffers.h"

#include <array>
#include <cstdint>
#include <vector>

namespace facesketch {

class GpuCulling {
public:
    /// Computes everything from `curvature`'s current batch, which need not outlive this object.
    GpuCulling(gpu::Device& device, const GpuCurvature& curvature);
    ~GpuCulling();
    GpuCulling(const GpuCulling&) = delete;
    GpuCulling& operator=(const GpuCulling&) = delete;

    /// Brings everything up to date with `curvature` (the one it was built from): the bounds
    /// when its positions changed since the last update, the cones and locks when its shapes
    /// did (GpuCurvature::positionsVersion, shapesVersion). Returns whether anything changed.
    bool update(const GpuCurvature& curvature);

    /// Per vertex, a sphere holding that vertex in every mesh of the batch: centre xyz and
    /// radius, mm. Empty while the curvature holds no meshes.
    const std::vector<std::array<double, 4>>& vertexBounds() const { return vertexBounds_; }
    /// Per vertex, a cone holding the normal the contour tests read (the packed one) in every
    /// mesh where the vertex has a tangent plane: unit axis xyz and half-angle in radians, pi
    /// where nothing narrower holds. Empty until the curvature has shapes (GpuCurvature::hasShapes).
    const std::vector<std::array<double, 4>>& normalCones() const { return normalCones_; }
    /// One bit per (mesh, vertex), bit i % 32 of texel i / 32 for batch index i: set where k_r
    /// has one sign on the vertex's closed one-ring whatever the view (k1 and k2 of one sign at
    /// the vertex and at each neighbour with a tangent plane), so that no zero crossing of k_r,
    /// no suggestive contour, can touch it. All clear until the curvature has shapes.
    const gpu::TexelView& signLockTexels() const { return signLockTexels_; }
    const gpu::Buffer& signLocks() const { return signLocks_; }
    /// The one-rings of the topology (geometry/wedges.h), which the sign locks are taken over.
    const Neighbours& rings() const { return rings_; }

private:
    void setBounds(const GpuCurvature& curvature);
    void setConesAndLocks(const GpuCurvature& curvature);

    gpu::Device& device_;
    std::uint64_t positionsVersion_, shapesVersion_; // the curvature's, at the last update
    Neighbours rings_;
    std::vector<std::array<double, 4>> vertexBounds_, normalCones_;
    gpu::Buffer signLocks_;
    gpu::TexelView signLockTexels_;
};

} // namespace facesketch

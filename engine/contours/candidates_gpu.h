#pragma once
// The candidate cloud on the GPU (thesis 4.4): the per-view contour tests of
// contours/candidates.h for every face whose curvature a GpuCurvature holds, appended to one
// compact list with an atomic counter, then put in (mesh, vertex) order on the host (a counting
// sort) so that the result does not depend on GPU scheduling. Two dispatches (shaders/shared.h
// explains the choices): pass 1 computes every pair's radial curvature and own tests and lists
// the pairs that passed one (about a sixth); pass 2, dispatched indirectly at that size, runs
// the one-ring zero-crossing test, culls to the rectangle and sphere and appends. Pass 1 visits
// only the vertices that some face may show inside the culling rectangle and sphere (from
// per-vertex bounding spheres over the batch) and their one-rings: a stroke's box costs a
// fraction of a whole view. Nor does it visit the vertices that face away from the camera in
// every face (from per-vertex normal cones, contours/curvature_gpu.h): on 230 synthetic faces,
// 15% of the vertices in a three-quarter view and 35% in a profile. Pairs whose one-ring keeps
// one sign of k_r for any view (GpuCurvature::signLockTexels) skip the zero-crossing test, which
// they cannot pass: even where the view runs exactly along a neighbour's normal (its k_r taken
// as 0), that neighbour is the end nearer zero, and it has no pre-test.
// Needs subgroup ballot in compute shaders (every desktop GPU and lavapipe have it) and texel
// buffers of #faces x #V texels (maxTexelBufferElements); throws Error naming what is missing.
//
//   GpuCandidates cloud(device, curvature, flags);           // once per dataset
//   std::vector<Candidate> c = cloud.build(camera, params);  // per view change or stroke

#include "contours/candidates.h"
#include "contours/curvature_gpu.h"
#include "geometry/wedges.h"

namespace facesketch {

/// The SPIR-V of the two passes. The built-in pair is shaders/contours_radial.comp.glsl and
/// shaders/contours.comp.glsl; another must keep their bindings and the radial word, and may
/// change the workgroup size (read from its SPIR-V). `facesketch bench contours --pass1 FILE
/// --pass2 FILE` times such a variant against the built-in kernels in one process.
struct ContourKernels {
    gpu::ShaderCode radial;   ///< pass 1
    gpu::ShaderCode contours; ///< pass 2
};
ContourKernels builtInContourKernels();

class GpuCandidates {
public:
    /// `curvature` must have run and must outlive this object; `flags` holds #V VertexFlag bits
    /// (or is empty). `kernels`' code need only live through the constructor.
    GpuCandidates(gpu::Device& device, GpuCurvature& curvature, const std::vector<std::uint32_t>& flags,
        const ContourKernels& kernels = builtInContourKernels());
    ~GpuCandidates();
    GpuCandidates(const GpuCandidates&) = delete;
    GpuCandidates& operator=(const GpuCandidates&) = delete;

    /// The candidates seen by `camera`, sorted by (mesh, vertex). Grows its output buffer and
    /// runs again when the cloud outgrows it. `timing`, if given, receives GPU ms of the last run.
    std::vector<Candidate> build(const Camera& camera, const ContourParams& params, double* timing = nullptr);
    /// The vertices the last build ran the kernels for (of #V): those some face may show in the
    /// rectangle and sphere without facing away, and their one-rings.
    std::uint32_t listedVertices() const { return listedVertices_; }

private:
    gpu::Device& device_;
    GpuCurvature& curvature_;
    void destroyBatchBuffers();

    static constexpr std::uint32_t kBindings = 13; // shaders/shared.h CONTOURS_BINDING_*
    gpu::ComputeProgram radialProgram_, program_;
    Neighbours rings_;                 // one-rings on the host, for listing the vertices a view needs
    std::vector<std::uint32_t> flags_; // VertexFlag per vertex, sent with the vertex list
    gpu::Buffer view_, neighbourOffsets_, neighbours_, vertexList_;
    gpu::TexelView neighbourOffsetTexels_, neighbourTexels_, vertexListTexels_;
    gpu::Buffer radial_; // the radial word per (mesh, vertex), between the two passes
    gpu::TexelView radialTexels_;
    gpu::Buffer work_; // pass 2's dispatch size and the pairs pass 1 listed for it
    gpu::TexelView workTexels_;
    gpu::Buffer output_;
    std::uint32_t capacity_ = 0;
    std::uint32_t listedVertices_ = 0;
    gpu::GpuTimer timer_;
};

} // namespace facesketch

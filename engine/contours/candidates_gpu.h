#pragma once
// The candidate cloud on the GPU (thesis 4.4): the per-view contour tests of
// contours/candidates.h for every face whose curvature a GpuCurvature holds, appended to one
// compact list with an atomic counter, then put in (mesh, vertex) order on the host (a counting
// sort) so that the result does not depend on GPU scheduling. Two dispatches (BENCHMARKS.md, "Why
// the kernels look as they do", explains the choices): pass 1 computes every pair's radial curvature and own tests and lists
// the pairs that passed one (about a sixth); pass 2, dispatched indirectly at that size, runs
// the one-ring zero-crossing test, culls to the rectangle and sphere and appends. Pass 1 visits
// only the vertices that some face may show inside the culling rectangle and sphere (from
// per-vertex bounding spheres over the batch) and their one-rings: a stroke's box costs a
// fraction of a whole view. Nor does it visit the vertices that face away from the camera in
// every face (from per-vertex normal cones). Pairs whose one-ring keeps one sign of k_r for any
// view (sign locks) skip the zero-crossing test, which they cannot pass: even where the view
// runs exactly along a neighbour's normal (its k_r taken as 0), that neighbour is the end nearer
// zero, and it has no pre-test. The bounds, cones and locks are a GpuCulling
// (contours/culling_gpu.h), kept up to date with the curvature: on 230 synthetic faces the cones
// leave out 15% of the vertices in a three-quarter view and 35% in a profile.
// Needs subgroup ballot in compute shaders (every desktop GPU and lavapipe have it) and texel
// buffers of #faces x #V texels (maxTexelBufferElements); throws Error naming what is missing.
//
//   GpuCandidates cloud(device, curvature, flags);           // once per dataset
//   std::vector<Candidate> c = cloud.build(camera, params);  // per view change or stroke
//
// build() is list(), record() into a one-shot command buffer, submit and wait, then collect().
// An app that overlaps the cloud with other GPU or host work calls the three itself:
//
//   if (cloud.list(camera, params) > 0) {   // host: which vertices to visit; uploads them
//       cloud.record(cmd);                  // into the app's command buffer, submitted by the app
//       submit(cmd, fence);                 // ... other work meanwhile ...
//   }
//   std::vector<Candidate> c = cloud.collect(fence);  // waits, reads back, sorts
//
// One view at a time per object: list() again only after collect().

#include "contours/candidates.h"
#include "contours/culling_gpu.h"
#include "contours/curvature_gpu.h"
#include "shaders/shared.h"

namespace facesketch {

/// The SPIR-V of the two passes. The built-in pair is shaders/contours_radial.comp.glsl and
/// shaders/contours.comp.glsl, whose pass 2 with rtsc's filter is the same file compiled with
/// CONTOURS_RTSC (a pipeline of its own: on lavapipe a branch costs both its sides, and the
/// crossing's test would slow the default filter's pass 2 twofold). Another pair must keep
/// their bindings and the radial word, and may change the workgroup size (read from its
/// SPIR-V). `facesketch bench contours --pass1 FILE --pass2 FILE` times such a variant (of the
/// default filter's pass 2) against the built-in kernels in one process.
struct ContourKernels {
    gpu::ShaderCode radial;       ///< pass 1
    gpu::ShaderCode contours;     ///< pass 2
    gpu::ShaderCode contoursRtsc; ///< pass 2 for SuggestiveFilter::RtscCrossing
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

    /// The candidates seen by `camera`, sorted by (mesh, vertex): list(), record() into a
    /// one-shot command buffer, submit, wait, collect(). `timing`, if given, receives GPU ms of
    /// the last run (0 when no vertex was listed).
    std::vector<Candidate> build(const Camera& camera, const ContourParams& params, double* timing = nullptr);

    /// Step 1, on the host: lists the vertices `camera` may need (those some face may show in
    /// the rectangle and sphere without facing away, and their one-rings), uploads the list and
    /// the view, and sizes the buffers. Returns how many it listed; with 0 there is nothing to
    /// record and collect() returns no candidates. Throws Error when the curvature holds no
    /// meshes or the batch exceeds the device's workgroup limits. Must not be called while a
    /// recording of this object is in flight (it rewrites what that reads).
    std::uint32_t list(const Camera& camera, const ContourParams& params);
    /// Step 2: records both passes of the listed view (and a GPU timer) into `cmd`, a command
    /// buffer in the recording state on this device's queue, outside a render pass. The caller
    /// submits it. Records nothing when list() listed nothing; throws Error without a list().
    void record(VkCommandBuffer cmd);
    /// Step 3: waits for `done` (the fence of the submission holding record()'s commands, or
    /// VK_NULL_HANDLE when the caller has waited for it already), reads the cloud back and sorts
    /// it by (mesh, vertex). When the cloud outgrew the output buffer, grows it and runs the
    /// view again itself (a one-shot submission, waited for). `timing` as in build(). Throws
    /// Error without a record(), gpu::GpuError when the wait fails (device lost).
    std::vector<Candidate> collect(VkFence done = VK_NULL_HANDLE, double* timing = nullptr);

    /// The vertices the last list() listed (of #V).
    std::uint32_t listedVertices() const { return listedVertices_; }
    /// The culling data the listing reads (updated by list() when the curvature changed).
    const GpuCulling& culling() const { return culling_; }

private:
    gpu::Device& device_;
    GpuCurvature& curvature_;
    GpuCulling culling_;
    void destroyBatchBuffers();
    void createOutput();

    gpu::ComputeProgram radialProgram_, program_, rtscProgram_;
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

    // The view between list(), record() and collect().
    enum class Step { None, Listed, Recorded };
    Step step_ = Step::None;
    shaders::ContourView viewData_ {};
};

} // namespace facesketch

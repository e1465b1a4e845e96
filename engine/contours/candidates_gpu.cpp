#include "contours/candidates_gpu.h"

#include "core/error.h"
#include "geometry/wedges.h"
#include "shaders/contours_comp.h"
#include "shaders/contours_radial_comp.h"
#include "shaders/contours_rtsc_comp.h"
#include "shaders/shared.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <span>

namespace facesketch {

namespace {

using shaders::ContourCandidate;
using shaders::ContourView;
constexpr VkDeviceSize outputHeader = CONTOURS_OUTPUT_HEADER * sizeof(std::uint32_t);

// Float limits for the "everything" defaults (1e30 fits in a float; larger would be inf).
float clampToFloat(double x)
{
    return static_cast<float>(std::clamp(x, -1e30, 1e30));
}

// Whether a sphere (centre, radius; world mm) can show any point inside the pixel rectangle:
// the eight corners of its eye-space bounding box, projected, bound its image while all lie in
// front of the camera; otherwise it is kept. Half a pixel of slack covers the kernel's float
// arithmetic.
bool sphereMayShow(const Camera& camera, const std::array<double, 4>& sphere, const double rect[4])
{
    const glm::dvec4 centre = camera.view * glm::dvec4(sphere[0], sphere[1], sphere[2], 1.0);
    const double r = sphere[3];
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec4 corner = centre + glm::dvec4(k & 1 ? r : -r, k & 2 ? r : -r, k & 4 ? r : -r, 0.0);
        const glm::dvec4 clip = camera.projection * corner;
        if (!(clip.w > 1e-9))
            return true;
        const double x = (clip.x / clip.w + 1.0) * 0.5 * camera.width, y = (1.0 - clip.y / clip.w) * 0.5 * camera.height;
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
    }
    constexpr double slack = 0.5;
    return x1 >= rect[0] - slack && x0 <= rect[2] + slack && y1 >= rect[1] - slack && y0 <= rect[3] + slack;
}

// An upper bound of n . v, the normal's cosine to the direction towards the camera, over every
// point of the vertex's bounding sphere and every normal in its cone (both over the batch):
// the smallest angle between the cone and the directions from the sphere to the eye.
double maxFacing(const Camera& camera, const std::array<double, 4>& sphere, const std::array<double, 4>& cone)
{
    if (cone[3] >= M_PI)
        return 1;
    glm::dvec3 towards = -glm::normalize(camera.forward);
    double spread = 0;
    if (camera.kind == Projection::Perspective) {
        const glm::dvec3 toEye = camera.eye - glm::dvec3(sphere[0], sphere[1], sphere[2]);
        const double distance = glm::length(toEye);
        if (!(distance > sphere[3] * (1 + 1e-9) + 1e-9))
            return 1;
        towards = toEye / distance;
        spread = std::asin(sphere[3] / distance);
    }
    const glm::dvec3 axis(cone[0], cone[1], cone[2]);
    const double axisAngle = std::atan2(glm::length(glm::cross(axis, towards)), glm::dot(axis, towards));
    const double gap = axisAngle - cone[3] - spread;
    return gap <= 0 ? 1.0 : std::cos(std::min(gap, M_PI));
}

// The appended candidates in (mesh, vertex) order, so that the result does not depend on GPU
// scheduling: a stable counting sort by vertex, then by mesh, linear in the candidates (a
// comparison sort of a view's 109,000 took 8 ms, as long as pass 2). Throws Error on an id out
// of range, which only a broken kernel could write.
std::vector<Candidate> sortedCandidates(std::span<const ContourCandidate> raw, std::uint32_t meshCount, std::uint32_t vertexCount)
{
    std::vector<std::uint32_t> start(std::max(meshCount, vertexCount) + 1), byVertex(raw.size());
    for (const ContourCandidate& c : raw) {
        if (c.ids[0] >= meshCount || c.ids[1] >= vertexCount)
            fail("GpuCandidates: the kernel appended mesh ", c.ids[0], " vertex ", c.ids[1], " of ", meshCount, " x ", vertexCount);
        ++start[c.ids[1] + 1];
    }
    for (std::uint32_t v = 0; v < vertexCount; ++v)
        start[v + 1] += start[v];
    for (std::uint32_t i = 0; i < raw.size(); ++i)
        byVertex[start[raw[i].ids[1]]++] = i;
    std::fill(start.begin(), start.end(), 0);
    for (const ContourCandidate& c : raw)
        ++start[c.ids[0] + 1];
    for (std::uint32_t m = 0; m < meshCount; ++m)
        start[m + 1] += start[m];
    std::vector<Candidate> out(raw.size());
    for (const std::uint32_t i : byVertex) {
        const ContourCandidate& g = raw[i];
        Candidate& c = out[start[g.ids[0]]++];
        c.mesh = g.ids[0];
        c.vertex = g.ids[1];
        c.types = g.ids[2];
        c.world[0] = g.world[0];
        c.world[1] = g.world[1];
        c.world[2] = g.world[2];
        c.depth = g.world[3];
        c.screen[0] = g.pixel[0];
        c.screen[1] = g.pixel[1];
    }
    return out;
}

} // namespace

ContourKernels builtInContourKernels()
{
    return { gpu::shaderCode(contours_radial_comp), gpu::shaderCode(contours_comp), gpu::shaderCode(contours_rtsc_comp) };
}

GpuCandidates::GpuCandidates(
    gpu::Device& device, GpuCurvature& curvature, const std::vector<std::uint32_t>& flags, const ContourKernels& kernels)
    : device_(device)
    , curvature_(curvature)
    , culling_(device, curvature)
{
    const auto nv = static_cast<size_t>(curvature.vertexCount());
    if (!flags.empty() && flags.size() != nv)
        fail("GpuCandidates: ", flags.size(), " vertex flags for ", nv, " vertices");
    // Pass 1 lists pairs with one atomic per subgroup (shaders/contours_radial.comp.glsl).
    auto subgroup = gpu::makeStruct<VkPhysicalDeviceSubgroupProperties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES);
    auto properties = gpu::makeStruct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2);
    properties.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(device_.physical, &properties);
    if (!(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) || !(subgroup.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT))
        fail("GpuCandidates: the device (", device_.name, ") has no subgroup ballot in compute shaders");
    radialProgram_
        = gpu::createComputeProgram(device_, kernels.radial, CONTOURS_BINDING_COUNT, 0, CONTOURS_UNIFORM_BINDINGS, CONTOURS_TEXEL_BINDINGS);
    try { // a variant's pass 2 may be what fails (ContourKernels): release what was made
        program_ = gpu::createComputeProgram(
            device_, kernels.contours, CONTOURS_BINDING_COUNT, 0, CONTOURS_UNIFORM_BINDINGS, CONTOURS_TEXEL_BINDINGS);
        rtscProgram_ = gpu::createComputeProgram(
            device_, kernels.contoursRtsc, CONTOURS_BINDING_COUNT, 0, CONTOURS_UNIFORM_BINDINGS, CONTOURS_TEXEL_BINDINGS);
    } catch (...) {
        gpu::destroyComputeProgram(device_, program_);
        gpu::destroyComputeProgram(device_, radialProgram_);
        throw;
    }
    const Neighbours& rings = culling_.rings();
    // A vertex without neighbours (isolated) still needs a non-empty buffer.
    const std::vector<std::uint32_t> ringVertices = rings.vertices.empty() ? std::vector<std::uint32_t> { 0 } : rings.vertices;
    flags_ = flags.empty() ? std::vector<std::uint32_t>(nv, 0) : flags;
    auto table = [&](gpu::Buffer& buffer, gpu::TexelView& view, const std::uint32_t* data, size_t count, int words) {
        buffer = gpu::createBuffer(device_, count * words * sizeof(std::uint32_t), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
        if (data)
            gpu::uploadBuffer(device_, buffer, data, buffer.size);
        view = gpu::createTexelView(device_, buffer, words == 2 ? VK_FORMAT_R32G32_UINT : VK_FORMAT_R32_UINT);
    };
    table(vertexList_, vertexListTexels_, nullptr, nv, 2);
    table(neighbourOffsets_, neighbourOffsetTexels_, rings.offsets.data(), rings.offsets.size(), 1);
    table(neighbours_, neighbourTexels_, ringVertices.data(), ringVertices.size(), 1);
    view_ = gpu::createBuffer(device_, sizeof(ContourView), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    timer_ = gpu::createGpuTimer(device_);
}

GpuCandidates::~GpuCandidates()
{
    vkDeviceWaitIdle(device_.device);
    gpu::destroyGpuTimer(device_, timer_);
    if (output_.buffer)
        gpu::destroyBuffer(device_, output_);
    destroyBatchBuffers();
    gpu::destroyBuffer(device_, view_);
    for (auto [buffer, view] : { std::pair { &neighbours_, &neighbourTexels_ }, std::pair { &neighbourOffsets_, &neighbourOffsetTexels_ },
             std::pair { &vertexList_, &vertexListTexels_ } }) {
        gpu::destroyTexelView(device_, *view);
        gpu::destroyBuffer(device_, *buffer);
    }
    gpu::destroyComputeProgram(device_, rtscProgram_);
    gpu::destroyComputeProgram(device_, program_);
    gpu::destroyComputeProgram(device_, radialProgram_);
}

void GpuCandidates::destroyBatchBuffers()
{
    if (!radial_.buffer)
        return;
    gpu::destroyTexelView(device_, workTexels_);
    gpu::destroyBuffer(device_, work_);
    gpu::destroyTexelView(device_, radialTexels_);
    gpu::destroyBuffer(device_, radial_);
}

void GpuCandidates::createOutput()
{
    output_
        = gpu::createBuffer(device_, outputHeader + VkDeviceSize(capacity_) * sizeof(ContourCandidate), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

std::vector<Candidate> GpuCandidates::build(const Camera& camera, const ContourParams& params, double* timing)
{
    if (list(camera, params) > 0)
        gpu::submitAndWait(device_, [&](VkCommandBuffer cmd) { record(cmd); });
    return collect(VK_NULL_HANDLE, timing);
}

std::uint32_t GpuCandidates::list(const Camera& camera, const ContourParams& p)
{
    step_ = Step::None;
    const std::uint32_t meshCount = curvature_.meshCount();
    const auto vertexCount = static_cast<std::uint32_t>(curvature_.vertexCount());
    if (meshCount == 0)
        fail("GpuCandidates::list: the curvature holds no meshes");
    const VkDeviceSize perVertex = VkDeviceSize(meshCount) * vertexCount * sizeof(std::uint32_t);
    const std::uint64_t pairGroups = (std::uint64_t(meshCount) * vertexCount + CONTOURS_GROUP_PAIRS - 1) / CONTOURS_GROUP_PAIRS;
    if (pairGroups > device_.properties.limits.maxComputeWorkGroupCount[0])
        fail("GpuCandidates::list: ", meshCount, " faces of ", vertexCount, " vertices may need ", pairGroups,
            " workgroups in pass 2, more than this device's limit of ", device_.properties.limits.maxComputeWorkGroupCount[0]);
    culling_.update(curvature_);
    if (radial_.size != perVertex) { // first build, or the curvature now holds another batch
        vkDeviceWaitIdle(device_.device);
        destroyBatchBuffers();
        const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
        radial_ = gpu::createBuffer(device_, perVertex, usage);
        radialTexels_ = gpu::createTexelView(device_, radial_, VK_FORMAT_R32_UINT);
        work_ = gpu::createBuffer(
            device_, CONTOURS_WORK_HEADER * sizeof(std::uint32_t) + perVertex, usage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
        workTexels_ = gpu::createTexelView(device_, work_, VK_FORMAT_R32_UINT);
    }
    // The vertices that may be a candidate in some mesh: inside the rectangle and the culling
    // sphere, and not facing away (n . v <= -silhouetteThreshold) everywhere; and the one-rings
    // of those that may pass the suggestive pre-test (n . v > 0), whose radial curvature the
    // zero-crossing test reads. A vertex left out would give no candidate and be read by none:
    // the cloud is the same. The facing bound allows 1e-4 for the kernels' float arithmetic.
    const std::vector<std::array<double, 4>>& bounds = culling_.vertexBounds();
    const std::vector<std::array<double, 4>>& cones = culling_.normalCones();
    const Neighbours& rings = culling_.rings();
    std::vector<char> candidate(vertexCount, 0), pretest(vertexCount, 0), listed(vertexCount, 0);
    const bool everything = p.rect[0] <= -1e29 && p.rect[1] <= -1e29 && p.rect[2] >= 1e29 && p.rect[3] >= 1e29 && p.sphere[3] >= 1e29;
    for (std::uint32_t v = 0; v < vertexCount; ++v) {
        const auto& b = bounds[v];
        const double apart = std::sqrt(std::pow(b[0] - p.sphere[0], 2) + std::pow(b[1] - p.sphere[1], 2) + std::pow(b[2] - p.sphere[2], 2));
        if (!everything && !(apart - b[3] <= p.sphere[3] * (1 + 1e-6) + 1e-3 && sphereMayShow(camera, b, p.rect)))
            continue;
        const double facing = cones.empty() ? 1.0 : maxFacing(camera, b, cones[v]);
        candidate[v] = facing > -p.silhouetteThreshold - 1e-4;
        pretest[v] = facing > -1e-4;
    }
    for (std::uint32_t v = 0; v < vertexCount; ++v) {
        listed[v] |= candidate[v];
        if (pretest[v])
            for (std::uint32_t k = rings.offsets[v]; k < rings.offsets[v + 1]; ++k)
                listed[rings.vertices[k]] = 1;
    }
    std::vector<std::uint32_t> entries; // vertex, flags
    for (std::uint32_t v = 0; v < vertexCount; ++v)
        if (listed[v]) {
            entries.push_back(v);
            entries.push_back(flags_[v]);
        }
    const auto listCount = static_cast<std::uint32_t>(entries.size() / 2);
    listedVertices_ = listCount;
    step_ = Step::Listed;
    if (listCount == 0)
        return 0;
    gpu::uploadBuffer(device_, vertexList_, entries.data(), entries.size() * sizeof(std::uint32_t));
    const std::uint64_t groupsY = (listCount + radialProgram_.localSize[1] - 1) / radialProgram_.localSize[1];
    if (groupsY > device_.properties.limits.maxComputeWorkGroupCount[1]) {
        step_ = Step::None;
        fail("GpuCandidates::list: ", listCount, " vertices need ", groupsY, " workgroups in pass 1, more than this device's limit of ",
            device_.properties.limits.maxComputeWorkGroupCount[1]);
    }

    if (capacity_ == 0) {
        // A view's cloud is typically a few percent of all vertices; grown on demand by collect().
        capacity_ = std::max<std::uint32_t>(1024, meshCount * vertexCount / 16);
        createOutput();
    }

    ContourView& view = viewData_;
    view = ContourView {};
    view.viewProjection = glm::mat4(camera.projection * camera.view);
    view.eye
        = camera.kind == Projection::Perspective ? glm::vec4(glm::vec3(camera.eye), 1.0f) : glm::vec4(glm::vec3(-camera.forward), 0.0f);
    view.rect = { clampToFloat(p.rect[0]), clampToFloat(p.rect[1]), clampToFloat(p.rect[2]), clampToFloat(p.rect[3]) };
    view.sphere = { float(p.sphere[0]), float(p.sphere[1]), float(p.sphere[2]), clampToFloat(p.sphere[3]) };
    if (p.suggestiveFilter == SuggestiveFilter::RtscCrossing && !(p.rtscThreshold >= 0 && std::isfinite(p.rtscThreshold)))
        fail("GpuCandidates: rtsc threshold ", p.rtscThreshold, " must be finite and not negative");
    // w: rtsc's threshold, or -1 for the vertex-strength filter (shaders/shared.h).
    const float rtsc = p.suggestiveFilter == SuggestiveFilter::RtscCrossing ? float(p.rtscThreshold) : -1.0f;
    view.thresholds = { float(p.silhouetteThreshold), float(p.suggestiveThreshold), float(p.featureSize * p.featureSize), rtsc };
    view.screen = { float(camera.width), float(camera.height), 0.0f, 0.0f };
    view.counts = { vertexCount, meshCount, capacity_, listCount };
    gpu::uploadBuffer(device_, view_, &view, sizeof(view));
    return listCount;
}

void GpuCandidates::record(VkCommandBuffer cmd)
{
    if (step_ == Step::None)
        fail("GpuCandidates::record: no view listed (call list() first)");
    step_ = Step::Recorded;
    const std::uint32_t meshCount = viewData_.counts[1], listCount = viewData_.counts[3];
    if (listedVertices_ == 0)
        return;
    // Pass 1: one invocation per listed vertex and CONTOURS_MESHES_PER_INVOCATION meshes; a
    // row of BATCH_GROUP_MESHES invocations along x does 64 neighbouring meshes, interleaved
    // (shaders/contours_radial.comp.glsl). No kernel loops over vertices.
    const std::uint32_t meshInvocations = (meshCount + CONTOURS_MESHES_PER_INVOCATION - 1) / CONTOURS_MESHES_PER_INVOCATION;
    gpu::timerStart(cmd, timer_);
    vkCmdFillBuffer(cmd, output_.buffer, 0, outputHeader, 0);
    const std::uint32_t workHeader[CONTOURS_WORK_HEADER] = { 0, 1, 1, 0 }; // pass 2's size (x, y, z), pairs
    vkCmdUpdateBuffer(cmd, work_.buffer, 0, sizeof(workHeader), workHeader);
    gpu::transferToComputeBarrier(cmd);
    const std::initializer_list<gpu::Binding> buffers
        = { &curvature_.positionTexels(), &curvature_.shapeTexels(), &curvature_.c23Texels(), &vertexListTexels_, &view_, &radial_,
              &radialTexels_, &neighbourOffsetTexels_, &neighbourTexels_, &output_, &work_, &workTexels_, &culling_.signLockTexels() };
    gpu::dispatchRaw(device_, cmd, radialProgram_, meshInvocations, listCount, 1, buffers, nullptr, 0);
    gpu::computeToIndirectBarrier(cmd);
    const bool rtsc = viewData_.thresholds[3] >= 0; // rtsc's filter (list())
    gpu::dispatchIndirect(device_, cmd, rtsc ? rtscProgram_ : program_, work_, 0, buffers, nullptr, 0);
    gpu::hostReadBarrier(cmd);
    gpu::timerEnd(cmd, timer_);
}

std::vector<Candidate> GpuCandidates::collect(VkFence done, double* timing)
{
    if (step_ == Step::None || (step_ == Step::Listed && listedVertices_ > 0))
        fail("GpuCandidates::collect: no view recorded (call list() and record() first)");
    step_ = Step::None;
    if (listedVertices_ == 0) {
        if (timing)
            *timing = 0;
        return {};
    }
    if (done != VK_NULL_HANDLE)
        if (VkResult r = vkWaitForFences(device_.device, 1, &done, VK_TRUE, UINT64_MAX); r != VK_SUCCESS)
            gpu::gpuFail("waiting for the candidate cloud's GPU work (vkWaitForFences)", r);
    const std::uint32_t meshCount = viewData_.counts[1], vertexCount = viewData_.counts[0];
    for (;;) {
        if (timing)
            *timing = gpu::timerMilliseconds(device_, timer_);
        std::uint32_t count = 0;
        gpu::readbackBuffer(device_, output_, &count, sizeof(count));
        if (count > capacity_) {
            vkDeviceWaitIdle(device_.device);
            gpu::destroyBuffer(device_, output_);
            capacity_ = count + count / 4;
            createOutput();
            viewData_.counts[2] = capacity_;
            gpu::uploadBuffer(device_, view_, &viewData_, sizeof(viewData_));
            step_ = Step::Listed;
            gpu::submitAndWait(device_, [&](VkCommandBuffer cmd) { record(cmd); });
            step_ = Step::None;
            continue;
        }
        // Sorted straight from the output where the device shares memory with the host (lavapipe):
        // allocating and copying a whole view's 5 MB first took about 1 ms of its 6 ms on the host.
        if (output_.mapped)
            return sortedCandidates(
                { reinterpret_cast<const ContourCandidate*>(static_cast<const char*>(output_.mapped) + outputHeader), count }, meshCount,
                vertexCount);
        std::vector<ContourCandidate> raw(count);
        if (count)
            gpu::readbackBuffer(device_, output_, raw.data(), raw.size() * sizeof(ContourCandidate), outputHeader);
        return sortedCandidates(raw, meshCount, vertexCount);
    }
}

} // namespace facesketch

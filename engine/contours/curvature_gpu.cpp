#include "contours/curvature_gpu.h"

#include "core/error.h"
#include "geometry/mesh_batch.h"
#include "geometry/wedges.h"
#include "shaders/curvature_comp.h"
#include "shaders/curvature_derivative_comp.h"
#include "shaders/normals_comp.h"
#include "shaders/shared.h"

#include <algorithm>
#include <cmath>

namespace facesketch {

namespace {

struct alignas(16) NormalsConstants {
    std::uint32_t vertexCount;
    std::uint32_t meshCount;
    std::uint32_t weighting;
};

struct alignas(16) BatchConstants {
    std::uint32_t vertexCount;
    std::uint32_t meshCount;
};

// Batch-layout vec4 buffer back to mesh-major with `components` floats per vertex.
std::vector<float> downloadBatch(gpu::Device& device, const gpu::Buffer& buffer, std::uint32_t meshCount, Eigen::Index vertexCount,
                                 int components)
{
    const size_t n = static_cast<size_t>(meshCount) * vertexCount;
    std::vector<float> batch(4 * n);
    gpu::readbackBuffer(device, buffer, batch.data(), batch.size() * sizeof(float));
    std::vector<float> out(components * n);
    for (size_t v = 0; v < static_cast<size_t>(vertexCount); ++v)
        for (size_t m = 0; m < meshCount; ++m)
            for (int c = 0; c < components; ++c)
                out[components * (m * vertexCount + v) + c] = batch[4 * (v * meshCount + m) + c];
    return out;
}

} // namespace

GpuCurvature::GpuCurvature(gpu::Device& device, const Triangles& F, Eigen::Index vertexCount) : device_(device), vertexCount_(vertexCount)
{
    if (vertexCount <= 0 || F.rows() == 0)
        fail("GpuCurvature: need at least one vertex and one triangle (got ", vertexCount, " and ", F.rows(), ")");
    const Wedges w = buildWedges(F, vertexCount);
    normalsProgram_ = gpu::createComputeProgram(device_, gpu::shaderCode(normals_comp), 4, sizeof(NormalsConstants));
    curvatureProgram_ = gpu::createComputeProgram(device_, gpu::shaderCode(curvature_comp), 6, sizeof(BatchConstants));
    derivativeProgram_ = gpu::createComputeProgram(device_, gpu::shaderCode(curvature_derivative_comp), 7, sizeof(BatchConstants));
    wedgeOffsets_ = gpu::createBuffer(device_, w.offsets.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    wedges_ = gpu::createBuffer(device_, w.corners.size() * sizeof(w.corners[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    gpu::uploadBuffer(device_, wedgeOffsets_, w.offsets.data(), wedgeOffsets_.size);
    gpu::uploadBuffer(device_, wedges_, w.corners.data(), wedges_.size);
    timer_ = gpu::createGpuTimer(device_);
}

GpuCurvature::~GpuCurvature()
{
    vkDeviceWaitIdle(device_.device);
    gpu::destroyGpuTimer(device_, timer_);
    destroyBatchBuffers();
    gpu::destroyBuffer(device_, wedges_);
    gpu::destroyBuffer(device_, wedgeOffsets_);
    gpu::destroyComputeProgram(device_, derivativeProgram_);
    gpu::destroyComputeProgram(device_, curvatureProgram_);
    gpu::destroyComputeProgram(device_, normalsProgram_);
}

void GpuCurvature::destroyBatchBuffers()
{
    for (gpu::Buffer* b : {&derivatives_, &directions_, &curvature_, &normals_, &positions_})
        if (b->buffer)
            gpu::destroyBuffer(device_, *b);
}

void GpuCurvature::setPositions(const std::vector<float>& positions)
{
    const size_t stride = static_cast<size_t>(vertexCount_) * 3;
    if (positions.empty() || positions.size() % stride != 0)
        fail("GpuCurvature: ", positions.size(), " floats is not a whole number of meshes of ", vertexCount_, " vertices");
    for (size_t i = 0; i < positions.size(); ++i)
        if (!std::isfinite(positions[i]))
            fail("GpuCurvature: mesh ", i / stride, " vertex ", (i % stride) / 3, " has non-finite coordinate ", positions[i]);
    const std::uint32_t meshCount = static_cast<std::uint32_t>(positions.size() / stride);
    const VkDeviceSize bytes = VkDeviceSize(meshCount) * vertexCount_ * 4 * sizeof(float);
    if (!positions_.buffer || positions_.size != bytes) {
        vkDeviceWaitIdle(device_.device);
        destroyBatchBuffers();
        for (gpu::Buffer* b : {&positions_, &normals_, &curvature_, &directions_, &derivatives_})
            *b = gpu::createBuffer(device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    }
    meshCount_ = meshCount;
    const std::vector<float> batch = toBatchLayout(positions, meshCount_, static_cast<size_t>(vertexCount_));
    gpu::uploadBuffer(device_, positions_, batch.data(), bytes);
}

double GpuCurvature::run()
{
    if (meshCount_ == 0)
        fail("GpuCurvature::run: no positions set");
    const auto vertices = static_cast<std::uint32_t>(vertexCount_);
    const NormalsConstants normalsConstants{vertices, meshCount_, NORMALS_WEIGHT_MAX};
    const BatchConstants constants{vertices, meshCount_};
    const std::uint32_t rows = batchRows(vertices, meshCount_, curvatureProgram_.localSize[0], curvatureProgram_.localSize[1]);
    gpu::submitAndWait(device_, [&](VkCommandBuffer cmd) {
        gpu::timerStart(cmd, timer_);
        gpu::dispatch(device_, cmd, normalsProgram_, meshCount_, rows, 1, {&positions_, &wedgeOffsets_, &wedges_, &normals_},
                      normalsConstants);
        gpu::computeBarrier(cmd);
        gpu::dispatch(device_, cmd, curvatureProgram_, meshCount_, rows, 1,
                      {&positions_, &wedgeOffsets_, &wedges_, &normals_, &curvature_, &directions_}, constants);
        gpu::computeBarrier(cmd);
        gpu::dispatch(device_, cmd, derivativeProgram_, meshCount_, rows, 1,
                      {&positions_, &wedgeOffsets_, &wedges_, &normals_, &curvature_, &directions_, &derivatives_}, constants);
        gpu::hostReadBarrier(cmd);
        gpu::timerEnd(cmd, timer_);
    });
    return gpu::timerMilliseconds(device_, timer_);
}

GpuCurvature::Result GpuCurvature::download()
{
    Result r;
    r.normal = downloadBatch(device_, normals_, meshCount_, vertexCount_, 3);
    r.curvature = downloadBatch(device_, curvature_, meshCount_, vertexCount_, 4);
    r.direction = downloadBatch(device_, directions_, meshCount_, vertexCount_, 3);
    r.derivative = downloadBatch(device_, derivatives_, meshCount_, vertexCount_, 4);
    return r;
}

} // namespace facesketch

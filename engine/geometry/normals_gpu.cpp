#include "geometry/normals_gpu.h"

#include "core/error.h"
#include "geometry/mesh_batch.h"
#include "shaders/normals_comp.h"
#include "shaders/shared.h"

#include <algorithm>
#include <cmath>

namespace facesketch {

using shaders::NormalsConstants;

GpuNormals::GpuNormals(gpu::Device& device, const Triangles& F, Eigen::Index vertexCount)
    : device_(device)
    , vertexCount_(vertexCount)
{
    if (vertexCount <= 0 || F.rows() == 0)
        fail("GpuNormals: need at least one vertex and one triangle (got ", vertexCount, " and ", F.rows(), ")");
    program_ = gpu::createComputeProgram(
        device_, gpu::shaderCode(normals_comp), NORMALS_BINDING_COUNT, sizeof(NormalsConstants), 0, NORMALS_TEXEL_BINDINGS);
    uploadWedges(device_, F, vertexCount, wedgeOffsets_, wedges_);
    wedgeTexels_ = createWedgeTexels(device_, wedgeOffsets_, wedges_);
    timer_ = gpu::createGpuTimer(device_);
}

GpuNormals::~GpuNormals()
{
    vkDeviceWaitIdle(device_.device);
    gpu::destroyGpuTimer(device_, timer_);
    if (normals_.buffer)
        gpu::destroyBuffer(device_, normals_);
    if (positions_.buffer) {
        gpu::destroyTexelView(device_, positionTexels_);
        gpu::destroyBuffer(device_, positions_);
    }
    destroyWedgeTexels(device_, wedgeTexels_);
    gpu::destroyBuffer(device_, wedges_);
    gpu::destroyBuffer(device_, wedgeOffsets_);
    gpu::destroyComputeProgram(device_, program_);
}

void GpuNormals::setPositions(const std::vector<float>& positions)
{
    const size_t stride = static_cast<size_t>(vertexCount_) * 3;
    if (positions.empty() || positions.size() % stride != 0)
        fail("GpuNormals: ", positions.size(), " floats is not a whole number of meshes of ", vertexCount_, " vertices");
    for (size_t i = 0; i < positions.size(); ++i)
        if (!std::isfinite(positions[i]))
            fail("GpuNormals: mesh ", i / stride, " vertex ", (i % stride) / 3, " has non-finite coordinate ", positions[i]);
    const VkDeviceSize bytes = positions.size() / 3 * 4 * sizeof(float);
    if (!positions_.buffer || positions_.size < bytes) {
        vkDeviceWaitIdle(device_.device);
        if (positions_.buffer) {
            gpu::destroyTexelView(device_, positionTexels_);
            gpu::destroyBuffer(device_, positions_);
            gpu::destroyBuffer(device_, normals_);
        }
        positions_ = gpu::createBuffer(device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
        positionTexels_ = gpu::createTexelView(device_, positions_, VK_FORMAT_R32G32B32A32_SFLOAT);
        normals_ = gpu::createBuffer(device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    }
    meshCount_ = static_cast<std::uint32_t>(positions.size() / stride);
    const std::vector<float> batch = toBatchLayout(positions, meshCount_, static_cast<size_t>(vertexCount_));
    gpu::uploadBuffer(device_, positions_, batch.data(), bytes);
}

double GpuNormals::run()
{
    if (meshCount_ == 0)
        fail("GpuNormals::run: no positions set");
    const NormalsConstants constants { static_cast<std::uint32_t>(vertexCount_), meshCount_, NORMALS_WEIGHT_AREA };
    gpu::submitAndWait(device_, [&](VkCommandBuffer cmd) {
        gpu::timerStart(cmd, timer_);
        // Meshes along x, vertices along y, one (mesh, vertex) per invocation.
        const auto rows = batchRows(constants.vertexCount, program_.localSize[1]);
        gpu::dispatch(device_, cmd, program_, constants.meshCount, rows, 1,
            { &positionTexels_, &wedgeTexels_.offsets, &wedgeTexels_.corners, &normals_ }, constants);
        gpu::hostReadBarrier(cmd);
        gpu::timerEnd(cmd, timer_);
    });
    return gpu::timerMilliseconds(device_, timer_);
}

std::vector<float> GpuNormals::normals()
{
    std::vector<float> batch(static_cast<size_t>(meshCount_) * vertexCount_ * 4);
    gpu::readbackBuffer(device_, normals_, batch.data(), batch.size() * sizeof(float));
    return fromBatchLayout(batch, meshCount_, static_cast<size_t>(vertexCount_));
}

std::vector<float> vertexNormalsGpu(gpu::Device& device, const std::vector<float>& positions, const Triangles& F, Eigen::Index vertexCount)
{
    GpuNormals kernel(device, F, vertexCount);
    kernel.setPositions(positions);
    kernel.run();
    return kernel.normals();
}

} // namespace facesketch

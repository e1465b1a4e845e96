#include "contours/curvature_gpu.h"

#include "core/error.h"
#include "geometry/mesh_batch.h"
#include "shaders/curvature_comp.h"
#include "shaders/curvature_derivative_comp.h"
#include "shaders/normals_comp.h"
#include "shaders/shared.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facesketch {

namespace {

using shaders::BatchConstants;
using shaders::NormalsConstants;

// Batch-layout vec4 buffer back to mesh-major with `components` floats per vertex.
std::vector<float> downloadBatch(
    gpu::Device& device, const gpu::Buffer& buffer, std::uint32_t meshCount, Eigen::Index vertexCount, size_t components)
{
    const size_t n = static_cast<size_t>(meshCount) * vertexCount;
    std::vector<float> batch(4 * n);
    gpu::readbackBuffer(device, buffer, batch.data(), batch.size() * sizeof(float));
    return fromBatchLayout(batch, meshCount, static_cast<size_t>(vertexCount), components);
}

} // namespace

float halfToFloat(std::uint16_t h)
{
    const int exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
    const float sign = (h & 0x8000) ? -1.0f : 1.0f;
    if (exponent == 0)
        return sign * std::ldexp(static_cast<float>(mantissa), -24);
    if (exponent == 31)
        return mantissa ? std::numeric_limits<float>::quiet_NaN() : sign * std::numeric_limits<float>::infinity();
    return sign * std::ldexp(static_cast<float>(mantissa + 1024), exponent - 25);
}

Eigen::Vector3d octDecode(std::uint32_t packed)
{
    // unpackSnorm2x16: clamp(int16 / 32767, -1, 1), low half first.
    auto snorm = [](std::uint16_t bits) { return std::max(-1.0f, static_cast<std::int16_t>(bits) / 32767.0f); };
    const float fx = snorm(packed & 0xffff), fy = snorm(packed >> 16);
    Eigen::Vector3f n(fx, fy, 1.0f - std::abs(fx) - std::abs(fy));
    const float t = std::max(-n.z(), 0.0f);
    n.x() += n.x() >= 0.0f ? -t : t;
    n.y() += n.y() >= 0.0f ? -t : t;
    return n.normalized().cast<double>();
}

GpuCurvature::GpuCurvature(gpu::Device& device, const Triangles& F, Eigen::Index vertexCount)
    : device_(device)
    , vertexCount_(vertexCount)
{
    if (vertexCount <= 0 || F.rows() == 0)
        fail("GpuCurvature: need at least one vertex and one triangle (got ", vertexCount, " and ", F.rows(), ")");
    normalsProgram_ = gpu::createComputeProgram(
        device_, gpu::shaderCode(normals_comp), NORMALS_BINDING_COUNT, sizeof(NormalsConstants), 0, NORMALS_TEXEL_BINDINGS);
    curvatureProgram_ = gpu::createComputeProgram(
        device_, gpu::shaderCode(curvature_comp), CURVATURE_BINDING_COUNT, sizeof(BatchConstants), 0, CURVATURE_TEXEL_BINDINGS);
    derivativeProgram_ = gpu::createComputeProgram(
        device_, gpu::shaderCode(curvature_derivative_comp), DCURV_BINDING_COUNT, sizeof(BatchConstants), 0, DCURV_TEXEL_BINDINGS);
    uploadWedges(device_, F, vertexCount, wedgeOffsets_, wedges_);
    wedgeTexels_ = createWedgeTexels(device_, wedgeOffsets_, wedges_);
    hostWedges_ = buildWedges(F, vertexCount);
    timer_ = gpu::createGpuTimer(device_);
}

GpuCurvature::~GpuCurvature()
{
    vkDeviceWaitIdle(device_.device);
    gpu::destroyGpuTimer(device_, timer_);
    destroyBatchBuffers();
    destroyWedgeTexels(device_, wedgeTexels_);
    gpu::destroyBuffer(device_, wedges_);
    gpu::destroyBuffer(device_, wedgeOffsets_);
    gpu::destroyComputeProgram(device_, derivativeProgram_);
    gpu::destroyComputeProgram(device_, curvatureProgram_);
    gpu::destroyComputeProgram(device_, normalsProgram_);
}

void GpuCurvature::destroyBatchBuffers()
{
    for (gpu::TexelView* t : { &c23Texels_, &shapeTexels_, &directionTexels_, &curvatureTexels_, &normalTexels_, &positionTexels_ })
        if (t->view)
            gpu::destroyTexelView(device_, *t);
    for (gpu::Buffer* b : { &shapesC23_, &shapes_, &derivatives_, &directions_, &curvature_, &normals_, &positions_ })
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
        // The contour kernels read positions and shapes as texel buffers (gpu::TexelView).
        const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
        for (gpu::Buffer* b : { &positions_, &normals_, &curvature_, &directions_, &derivatives_, &shapes_ })
            *b = gpu::createBuffer(device_, bytes, usage);
        shapesC23_ = gpu::createBuffer(device_, bytes / 4, usage);
        positionTexels_ = gpu::createTexelView(device_, positions_, VK_FORMAT_R32G32B32A32_SFLOAT);
        normalTexels_ = gpu::createTexelView(device_, normals_, VK_FORMAT_R32G32B32A32_SFLOAT);
        curvatureTexels_ = gpu::createTexelView(device_, curvature_, VK_FORMAT_R32G32B32A32_SFLOAT);
        directionTexels_ = gpu::createTexelView(device_, directions_, VK_FORMAT_R32G32B32A32_SFLOAT);
        shapeTexels_ = gpu::createTexelView(device_, shapes_, VK_FORMAT_R32G32B32A32_UINT);
        c23Texels_ = gpu::createTexelView(device_, shapesC23_, VK_FORMAT_R32_UINT);
    }
    meshCount_ = meshCount;
    hasShapes_ = false; // until run() or uploadShapes()
    ++positionsVersion_;
    ++shapesVersion_;
    const std::vector<float> batch = toBatchLayout(positions, meshCount_, static_cast<size_t>(vertexCount_));
    gpu::uploadBuffer(device_, positions_, batch.data(), bytes);
}

double GpuCurvature::run()
{
    if (meshCount_ == 0)
        fail("GpuCurvature::run: no positions set");
    const auto vertices = static_cast<std::uint32_t>(vertexCount_);
    const NormalsConstants normalsConstants { vertices, meshCount_, NORMALS_WEIGHT_MAX };
    const BatchConstants constants { vertices, meshCount_ };
    const std::uint32_t rows = batchRows(vertices, curvatureProgram_.localSize[1]);
    shapesOnly_ = false;
    hasShapes_ = true;
    ++shapesVersion_;
    gpu::submitAndWait(device_, [&](VkCommandBuffer cmd) {
        gpu::timerStart(cmd, timer_);
        const WedgeTexels& w = wedgeTexels_;
        gpu::dispatch(
            device_, cmd, normalsProgram_, meshCount_, rows, 1, { &positionTexels_, &w.offsets, &w.corners, &normals_ }, normalsConstants);
        gpu::computeBarrier(cmd);
        gpu::dispatch(device_, cmd, curvatureProgram_, meshCount_, rows, 1,
            { &positionTexels_, &w.offsets, &w.corners, &normalTexels_, &curvature_, &directions_ }, constants);
        gpu::computeBarrier(cmd);
        gpu::dispatch(device_, cmd, derivativeProgram_, meshCount_, rows, 1,
            { &positionTexels_, &w.offsets, &w.corners, &normalTexels_, &curvatureTexels_, &directionTexels_, &derivatives_, &shapes_,
                &shapesC23_ },
            constants);
        gpu::hostReadBarrier(cmd);
        gpu::timerEnd(cmd, timer_);
    });
    return gpu::timerMilliseconds(device_, timer_);
}

GpuCurvature::PackedShapes GpuCurvature::downloadShapes()
{
    if (meshCount_ == 0)
        fail("GpuCurvature::downloadShapes: no positions set");
    const size_t n = static_cast<size_t>(meshCount_) * static_cast<size_t>(vertexCount_);
    PackedShapes p { std::vector<std::uint32_t>(4 * n), std::vector<std::uint32_t>(n) };
    gpu::readbackBuffer(device_, shapes_, p.shapes.data(), p.shapes.size() * 4);
    gpu::readbackBuffer(device_, shapesC23_, p.c23.data(), p.c23.size() * 4);
    return p;
}

void GpuCurvature::uploadShapes(const PackedShapes& p)
{
    const size_t n = static_cast<size_t>(meshCount_) * static_cast<size_t>(vertexCount_);
    if (meshCount_ == 0 || p.shapes.size() != 4 * n || p.c23.size() != n)
        fail("GpuCurvature::uploadShapes: ", p.shapes.size(), " shape words and ", p.c23.size(), " C23 words for ", meshCount_,
            " meshes of ", vertexCount_, " vertices");
    gpu::uploadBuffer(device_, shapes_, p.shapes.data(), p.shapes.size() * 4);
    gpu::uploadBuffer(device_, shapesC23_, p.c23.data(), p.c23.size() * 4);
    shapesOnly_ = true;
    hasShapes_ = true;
    ++shapesVersion_;
}

GpuCurvature::Result GpuCurvature::download()
{
    if (shapesOnly_)
        fail("GpuCurvature::download: only the packed shapes were restored (from a cache); run() computes the rest");
    Result r;
    r.normal = downloadBatch(device_, normals_, meshCount_, vertexCount_, 3);
    r.curvature = downloadBatch(device_, curvature_, meshCount_, vertexCount_, 4);
    r.direction = downloadBatch(device_, directions_, meshCount_, vertexCount_, 3);
    r.derivative = downloadBatch(device_, derivatives_, meshCount_, vertexCount_, 4);

    const size_t n = static_cast<size_t>(meshCount_) * vertexCount_;
    std::vector<std::uint32_t> shapes(4 * n), c23(n);
    gpu::readbackBuffer(device_, shapes_, shapes.data(), shapes.size() * 4);
    gpu::readbackBuffer(device_, shapesC23_, c23.data(), c23.size() * 4);
    r.packed.assign(12 * n, 0.0f);
    for (size_t v = 0; v < static_cast<size_t>(vertexCount_); ++v)
        for (size_t m = 0; m < meshCount_; ++m) {
            const size_t batch = v * meshCount_ + m, out = 12 * (m * vertexCount_ + v);
            const std::uint32_t* s = &shapes[4 * batch];
            if (s[0] == 0 && s[1] == 0)
                continue;
            const Eigen::Vector3d normal = octDecode(s[0]), dir1 = octDecode(s[1]);
            const std::uint32_t halves[3] = { s[2], s[3], c23[batch] };
            for (int k = 0; k < 3; ++k) {
                r.packed[out + k] = static_cast<float>(normal[k]);
                r.packed[out + 3 + k] = static_cast<float>(dir1[k]);
                r.packed[out + 6 + 2 * k] = halfToFloat(static_cast<std::uint16_t>(halves[k] & 0xffff));
                r.packed[out + 7 + 2 * k] = halfToFloat(static_cast<std::uint16_t>(halves[k] >> 16));
            }
        }
    return r;
}

} // namespace facesketch

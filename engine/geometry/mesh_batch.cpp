#include "geometry/mesh_batch.h"

#include "core/error.h"
#include "geometry/wedges.h"

#include <algorithm>

namespace facesketch {

namespace {
void checkSize(
    const std::vector<float>& data, std::size_t meshCount, std::size_t vertexCount, std::size_t floatsPerVertex, const char* what)
{
    if (data.size() != meshCount * vertexCount * floatsPerVertex)
        fail(what, ": ", data.size(), " floats, expected ", meshCount, " meshes x ", vertexCount, " vertices x ", floatsPerVertex);
}
} // namespace

std::vector<float> toBatchLayout(const std::vector<float>& meshMajor, std::size_t meshCount, std::size_t vertexCount)
{
    checkSize(meshMajor, meshCount, vertexCount, 3, "toBatchLayout");
    std::vector<float> batch(meshCount * vertexCount * 4, 0.0f);
    for (std::size_t m = 0; m < meshCount; ++m)
        for (std::size_t v = 0; v < vertexCount; ++v)
            for (std::size_t c = 0; c < 3; ++c)
                batch[4 * (v * meshCount + m) + c] = meshMajor[3 * (m * vertexCount + v) + c];
    return batch;
}

std::vector<float> fromBatchLayout(const std::vector<float>& batch, std::size_t meshCount, std::size_t vertexCount)
{
    checkSize(batch, meshCount, vertexCount, 4, "fromBatchLayout");
    std::vector<float> meshMajor(meshCount * vertexCount * 3);
    for (std::size_t v = 0; v < vertexCount; ++v)
        for (std::size_t m = 0; m < meshCount; ++m)
            for (std::size_t c = 0; c < 3; ++c)
                meshMajor[3 * (m * vertexCount + v) + c] = batch[4 * (v * meshCount + m) + c];
    return meshMajor;
}

std::vector<float> meshMajorPositions(const std::vector<Mesh>& meshes)
{
    std::vector<float> out;
    if (meshes.empty())
        return out;
    out.reserve(meshes.size() * static_cast<size_t>(meshes[0].V.size()));
    for (size_t m = 0; m < meshes.size(); ++m) {
        if (meshes[m].V.rows() != meshes[0].V.rows())
            fail("meshMajorPositions: mesh ", m, " has ", meshes[m].V.rows(), " vertices, mesh 0 has ", meshes[0].V.rows());
        for (Eigen::Index v = 0; v < meshes[m].V.rows(); ++v)
            for (int k = 0; k < 3; ++k)
                out.push_back(static_cast<float>(meshes[m].V(v, k)));
    }
    return out;
}

void uploadWedges(gpu::Device& device, const Triangles& F, Eigen::Index vertexCount, gpu::Buffer& offsets, gpu::Buffer& corners)
{
    const Wedges w = buildWedges(F, vertexCount);
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    offsets = gpu::createBuffer(device, w.offsets.size() * sizeof(std::uint32_t), usage);
    corners = gpu::createBuffer(device, w.corners.size() * sizeof(w.corners[0]), usage);
    gpu::uploadBuffer(device, offsets, w.offsets.data(), offsets.size);
    gpu::uploadBuffer(device, corners, w.corners.data(), corners.size);
}

WedgeTexels createWedgeTexels(gpu::Device& device, const gpu::Buffer& offsets, const gpu::Buffer& corners)
{
    return { gpu::createTexelView(device, offsets, VK_FORMAT_R32_UINT), gpu::createTexelView(device, corners, VK_FORMAT_R32G32_UINT) };
}

void destroyWedgeTexels(gpu::Device& device, WedgeTexels& texels)
{
    gpu::destroyTexelView(device, texels.corners);
    gpu::destroyTexelView(device, texels.offsets);
}

std::uint32_t batchRows(std::uint32_t vertexCount, std::uint32_t groupVertices)
{
    const std::uint64_t groups = (std::uint64_t(vertexCount) + groupVertices - 1) / groupVertices;
    if (groups > 65535)
        fail("a batch of ", vertexCount, " vertices needs ", groups, " workgroups along y, more than the 65535 every device has");
    return vertexCount;
}

} // namespace facesketch

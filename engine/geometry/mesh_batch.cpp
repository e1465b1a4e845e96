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

std::vector<float> fromBatchLayout(const std::vector<float>& batch, std::size_t meshCount, std::size_t vertexCount, std::size_t components)
{
    checkSize(batch, meshCount, vertexCount, 4, "fromBatchLayout");
    if (components < 1 || components > 4)
        fail("fromBatchLayout: ", components, " components per vertex, expected 1 to 4");
    std::vector<float> meshMajor(meshCount * vertexCount * components);
    for (std::size_t v = 0; v < vertexCount; ++v)
        for (std::size_t m = 0; m < meshCount; ++m)
            for (std::size_t c = 0; c < components; ++c)
                meshMajor[components * (m * vertexCount + v) + c] = batch[4 * (v * meshCount + m) + c];
    return meshMajor;
}

std::vector<float> meshMajorPositions(const std::vector<Mesh>& meshes)
{
    if (meshes.empty())
        return {};
    const Eigen::Index nv = meshes[0].V.rows();
    for (size_t m = 0; m < meshes.size(); ++m)
        if (meshes[m].V.rows() != nv)
            fail("meshMajorPositions: mesh ", m, " has ", meshes[m].V.rows(), " vertices, mesh 0 has ", nv);
    std::vector<float> out(meshes.size() * static_cast<size_t>(nv) * 3);
    for (size_t m = 0; m < meshes.size(); ++m)
        meshInBatch(out, nv, m) = meshes[m].V.cast<float>();
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

#include "geometry/mesh_batch.h"

#include "core/error.h"

#include <algorithm>

namespace facesketch {

namespace {
void checkSize(const std::vector<float>& data, std::size_t meshCount, std::size_t vertexCount, std::size_t floatsPerVertex,
               const char* what)
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

std::uint32_t batchRows(std::uint32_t vertexCount, std::uint32_t meshCount, std::uint32_t groupMeshes, std::uint32_t groupVertices,
                        std::uint32_t targetInvocations)
{
    const std::uint32_t columns = (meshCount + groupMeshes - 1) / groupMeshes * groupMeshes;
    std::uint32_t rows = std::max<std::uint32_t>(groupVertices, targetInvocations / std::max<std::uint32_t>(columns, 1));
    rows = (rows + groupVertices - 1) / groupVertices * groupVertices;
    return std::min({rows, vertexCount, 65535u * groupVertices});
}

} // namespace facesketch

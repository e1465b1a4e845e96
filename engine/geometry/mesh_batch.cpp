#include "geometry/mesh_batch.h"

#include "core/error.h"

namespace facesketch {

namespace {
void checkSize(const std::vector<float>& data, std::size_t meshCount, std::size_t vertexCount, const char* what)
{
    if (data.size() != meshCount * vertexCount * 3)
        fail(what, ": ", data.size(), " floats, expected ", meshCount, " meshes x ", vertexCount, " vertices x 3");
}
} // namespace

std::vector<float> toBatchLayout(const std::vector<float>& meshMajor, std::size_t meshCount, std::size_t vertexCount)
{
    checkSize(meshMajor, meshCount, vertexCount, "toBatchLayout");
    std::vector<float> batch(meshMajor.size());
    const std::size_t rows = vertexCount * 3;
    for (std::size_t m = 0; m < meshCount; ++m)
        for (std::size_t r = 0; r < rows; ++r)
            batch[r * meshCount + m] = meshMajor[m * rows + r];
    return batch;
}

std::vector<float> fromBatchLayout(const std::vector<float>& batch, std::size_t meshCount, std::size_t vertexCount)
{
    checkSize(batch, meshCount, vertexCount, "fromBatchLayout");
    std::vector<float> meshMajor(batch.size());
    const std::size_t rows = vertexCount * 3;
    for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t m = 0; m < meshCount; ++m)
            meshMajor[m * rows + r] = batch[r * meshCount + m];
    return meshMajor;
}

} // namespace facesketch

// Tests of geometry/mesh_batch: the GPU's batch layout against its definition, the mesh-major
// float array, wedges on the GPU.
#include "geometry/mesh_batch.h"

#include "core/error.h"
#include "geometry/primitives.h"
#include "geometry/wedges.h"
#include "test_common.h"

#include <vector>

using namespace facesketch;

namespace {
// 3 meshes x 5 vertices, every coordinate distinct: mesh m, vertex v, component c is
// 100 m + 10 v + c.
std::vector<float> numbered(std::size_t meshes, std::size_t vertices)
{
    std::vector<float> out;
    for (std::size_t m = 0; m < meshes; ++m)
        for (std::size_t v = 0; v < vertices; ++v)
            for (std::size_t c = 0; c < 3; ++c)
                out.push_back(float(100 * m + 10 * v + c));
    return out;
}
} // namespace

TEST_CASE("mesh_batch: the batch layout puts vertex v of mesh m at v * meshCount + m, w zero, and comes back")
{
    const std::vector<float> meshMajor = numbered(3, 5);
    const std::vector<float> batch = toBatchLayout(meshMajor, 3, 5);
    REQUIRE(batch.size() == 4 * 3 * 5);
    for (std::size_t m = 0; m < 3; ++m)
        for (std::size_t v = 0; v < 5; ++v) {
            for (std::size_t c = 0; c < 3; ++c)
                REQUIRE(batch[4 * (v * 3 + m) + c] == float(100 * m + 10 * v + c));
            REQUIRE(batch[4 * (v * 3 + m) + 3] == 0.0f);
        }
    REQUIRE(fromBatchLayout(batch, 3, 5) == meshMajor);
    REQUIRE_THROWS_WITH(toBatchLayout(meshMajor, 3, 4), Catch::Contains("toBatchLayout: 45 floats, expected 3 meshes x 4 vertices x 3"));
    REQUIRE_THROWS_WITH(fromBatchLayout(meshMajor, 3, 5), Catch::Contains("fromBatchLayout: 45 floats"));
}

TEST_CASE("mesh_batch: fromBatchLayout keeps the first 1 to 4 components of each vec4")
{
    std::vector<float> batch(4 * 2 * 3);
    for (std::size_t i = 0; i < batch.size(); ++i)
        batch[i] = float(i);
    const std::vector<float> four = fromBatchLayout(batch, 2, 3, 4), one = fromBatchLayout(batch, 2, 3, 1);
    REQUIRE(four.size() == batch.size());
    REQUIRE(one.size() == 6);
    for (std::size_t m = 0; m < 2; ++m)
        for (std::size_t v = 0; v < 3; ++v) {
            for (std::size_t c = 0; c < 4; ++c)
                REQUIRE(four[4 * (m * 3 + v) + c] == batch[4 * (v * 2 + m) + c]);
            REQUIRE(one[m * 3 + v] == batch[4 * (v * 2 + m)]);
        }
    REQUIRE_THROWS_WITH(fromBatchLayout(batch, 2, 3, 0), Catch::Contains("0 components"));
    REQUIRE_THROWS_WITH(fromBatchLayout(batch, 2, 3, 5), Catch::Contains("5 components"));
}

TEST_CASE("mesh_batch: meshMajorPositions lays meshes end to end as floats and refuses mixed vertex counts")
{
    const Mesh a = makeIcosphere(2.0, 1), b = makeIcosphere(3.0, 1), c = makeIcosphere(1.0, 0);
    const std::vector<float> p = meshMajorPositions({ a, b });
    const Eigen::Index nv = a.V.rows();
    REQUIRE(p.size() == static_cast<std::size_t>(2 * nv * 3));
    for (Eigen::Index v = 0; v < nv; ++v)
        for (int k = 0; k < 3; ++k) {
            REQUIRE(p[3 * v + k] == static_cast<float>(a.V(v, k)));
            REQUIRE(p[3 * (nv + v) + k] == static_cast<float>(b.V(v, k)));
        }
    REQUIRE(meshMajorPositions({}).empty());
    REQUIRE_THROWS_WITH(meshMajorPositions({ a, c }), Catch::Contains("mesh 1 has 12 vertices, mesh 0 has 42"));
}

TEST_CASE("mesh_batch: batchRows is one row per vertex, within the 65535 workgroups every device has")
{
    REQUIRE(batchRows(642, 8) == 642);
    REQUIRE(batchRows(65535 * 8, 8) == 65535 * 8);
    REQUIRE_THROWS_WITH(batchRows(65535 * 8 + 1, 8), Catch::Contains("65536 workgroups along y"));
}

TEST_CASE("mesh_batch: the wedges uploaded to the GPU read back as buildWedges made them, with texel views of their size")
{
    gpu::Device& d = test::device();
    const Mesh s = makeIcosphere(1.0, 1);
    const Wedges w = buildWedges(s.F, s.V.rows());
    gpu::Buffer offsets, corners;
    uploadWedges(d, s.F, s.V.rows(), offsets, corners);
    std::vector<std::uint32_t> gotOffsets(w.offsets.size());
    std::vector<std::array<std::uint32_t, 2>> gotCorners(w.corners.size());
    gpu::readbackBuffer(d, offsets, gotOffsets.data(), gotOffsets.size() * 4);
    gpu::readbackBuffer(d, corners, gotCorners.data(), gotCorners.size() * 8);
    REQUIRE(gotOffsets == w.offsets);
    REQUIRE(gotCorners == w.corners);
    WedgeTexels texels = createWedgeTexels(d, offsets, corners);
    REQUIRE(texels.offsets.elements == static_cast<VkDeviceSize>(s.V.rows() + 1));
    REQUIRE(texels.corners.elements == static_cast<VkDeviceSize>(3 * s.F.rows()));
    REQUIRE(texels.corners.format == VK_FORMAT_R32G32_UINT);
    destroyWedgeTexels(d, texels);
    gpu::destroyBuffer(d, corners);
    gpu::destroyBuffer(d, offsets);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

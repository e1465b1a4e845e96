#include "geometry/normals_gpu.h"
#include "core/error.h"
#include "core/random.h"
#include "geometry/normals.h"
#include "geometry/primitives.h"
#include "test_common.h"

#include <cmath>

using namespace facesketch;

// A batch of distinct, bumpy spheres: 5 meshes x 642 vertices (neither a multiple of 64).
static std::vector<float> bumpySpheres(const Mesh& s, int meshes)
{
    Random random(7);
    std::vector<float> positions;
    for (int m = 0; m < meshes; ++m)
        for (Eigen::Index v = 0; v < s.V.rows(); ++v) {
            const double r = random.uniform(0.8, 1.2);
            for (int c = 0; c < 3; ++c)
                positions.push_back(static_cast<float>(s.V(v, c) * r * (1 + 0.5 * m * (c == 0))));
        }
    return positions;
}

TEST_CASE("normals_gpu: matches the CPU reference on a batch of meshes")
{
    const Mesh s = makeIcosphere(50.0, 3);
    const std::vector<float> positions = bumpySpheres(s, 5);
    const std::vector<float> expected = vertexNormalsBatch(positions, s.F, s.V.rows());
    const std::vector<float> got = vertexNormalsGpu(test::device(), positions, s.F, s.V.rows());
    REQUIRE(got.size() == expected.size());
    for (size_t i = 0; i < got.size(); ++i) {
        if (std::abs(got[i] - expected[i]) > 1e-5f) {
            FAIL("first mismatch at mesh " << i / (3 * s.V.rows()) << " vertex " << (i / 3) % s.V.rows() << " component " << i % 3
                                           << ": gpu " << got[i] << " cpu " << expected[i]);
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("normals_gpu: reusing the kernel with a new, larger batch")
{
    const Mesh s = makeIcosphere(1.0, 1);
    GpuNormals kernel(test::device(), s.F, s.V.rows());
    for (int meshes : { 1, 4 }) {
        const std::vector<float> positions = bumpySpheres(s, meshes);
        kernel.setPositions(positions);
        kernel.run();
        const std::vector<float> got = kernel.normals();
        const std::vector<float> expected = vertexNormalsBatch(positions, s.F, s.V.rows());
        REQUIRE(got.size() == expected.size());
        for (size_t i = 0; i < got.size(); ++i)
            REQUIRE(got[i] == Approx(expected[i]).margin(1e-5));
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("normals_gpu: rejects a partial mesh and non-finite positions")
{
    const Mesh s = makeIcosphere(1.0, 0);
    GpuNormals kernel(test::device(), s.F, s.V.rows());
    REQUIRE_THROWS_WITH(kernel.setPositions(std::vector<float>(10, 0.0f)), Catch::Contains("not a whole number of meshes"));
    std::vector<float> positions(3 * s.V.rows(), 1.0f);
    positions[7] = NAN;
    REQUIRE_THROWS_WITH(kernel.setPositions(positions), Catch::Contains("vertex 2 has non-finite"));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

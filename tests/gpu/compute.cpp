#include "core/error.h"
#include "gpu/compute.h"
#include "shaders/normals_comp.h"
#include "shaders/shared.h"
#include "test_common.h"

using namespace facesketch;

TEST_CASE("compute: the workgroup size is read from the SPIR-V")
{
    std::uint32_t size[3] = {};
    gpu::readLocalSize(gpu::shaderCode(normals_comp), size);
    REQUIRE(size[0] == BATCH_GROUP_MESHES);
    REQUIRE(size[1] == BATCH_GROUP_VERTICES);
    REQUIRE(size[2] == 1);
}

TEST_CASE("compute: garbage is not mistaken for SPIR-V")
{
    const std::uint32_t garbage[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    std::uint32_t size[3];
    REQUIRE_THROWS_AS(gpu::readLocalSize(gpu::shaderCode(garbage), size), Error);
}

TEST_CASE("compute: a program builds and tears down cleanly under validation")
{
    gpu::Device& d = test::device();
    gpu::ComputeProgram p = gpu::createComputeProgram(d, gpu::shaderCode(normals_comp), 4, 16);
    REQUIRE(p.pipeline != VK_NULL_HANDLE);
    gpu::destroyComputeProgram(d, p);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

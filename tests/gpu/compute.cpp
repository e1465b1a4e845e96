#include "gpu/compute.h"
#include "core/error.h"
#include "gpu/buffers.h"
#include "shaders/normals_comp.h"
#include "shaders/shared.h"
#include "test_common.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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
    const std::uint32_t garbage[8] = { 1, 2, 3, 4, 5, 6, 7, 8 };
    std::uint32_t size[3];
    REQUIRE_THROWS_AS(gpu::readLocalSize(gpu::shaderCode(garbage), size), Error);
}

TEST_CASE("compute: a program builds and tears down cleanly under validation")
{
    gpu::Device& d = test::device();
    gpu::ComputeProgram p = gpu::createComputeProgram(d, gpu::shaderCode(normals_comp), 4, 16, 0, NORMALS_TEXEL_BINDINGS);
    REQUIRE(p.pipeline != VK_NULL_HANDLE);
    gpu::destroyComputeProgram(d, p);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("compute: a binding of the wrong kind is an error naming it, raised before anything is recorded")
{
    gpu::Device& d = test::device();
    gpu::ComputeProgram p = gpu::createComputeProgram(d, gpu::shaderCode(normals_comp), 4, 16, 0, NORMALS_TEXEL_BINDINGS);
    gpu::Buffer buffer = gpu::createBuffer(d, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    gpu::TexelView view = gpu::createTexelView(d, buffer, VK_FORMAT_R32_UINT);
    REQUIRE(view.elements == 16);
    const std::uint32_t constants[4] = { 1, 1, 0, 0 };
    VkCommandBuffer cmd = gpu::beginOneShot(d);
    REQUIRE_THROWS_WITH(gpu::dispatchRaw(d, cmd, p, 1, 1, 1, { &buffer, &view, &view, &buffer }, constants, sizeof(constants)),
        Catch::Contains("binding 0 needs a texel view"));
    REQUIRE_THROWS_WITH(gpu::dispatchRaw(d, cmd, p, 1, 1, 1, { &view, &view, &view, &view }, constants, sizeof(constants)),
        Catch::Contains("binding 3 needs a buffer"));
    gpu::endOneShotAndWait(d, cmd); // nothing was recorded: an empty submission
    gpu::destroyTexelView(d, view);
    gpu::destroyBuffer(d, buffer);
    gpu::destroyComputeProgram(d, p);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("compute: uniform and texel masks that overlap are refused")
{
    gpu::Device& d = test::device();
    REQUIRE_THROWS_WITH(gpu::createComputeProgram(d, gpu::shaderCode(normals_comp), 4, 16, 1u, NORMALS_TEXEL_BINDINGS),
        Catch::Contains("both uniform and texel"));
}

TEST_CASE("compute: a SPIR-V file reads back word for word, and a bad one is an error naming it")
{
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "facesketch_test_spirv";
    std::filesystem::create_directories(dir);
    const gpu::ShaderCode embedded = gpu::shaderCode(normals_comp);
    const auto write = [&](const std::string& name, const void* data, std::size_t bytes) {
        std::ofstream(dir / name, std::ios::binary).write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
        return dir / name;
    };
    const std::vector<std::uint32_t> words = gpu::readSpirvFile(write("normals.spv", embedded.words, embedded.sizeBytes));
    REQUIRE(words == std::vector<std::uint32_t>(embedded.words, embedded.words + embedded.sizeBytes / 4));

    const auto message = [](const std::filesystem::path& path) {
        try {
            gpu::readSpirvFile(path);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    REQUIRE_THAT(message(dir / "missing.spv"), Catch::Contains("missing.spv: cannot open"));
    REQUIRE_THAT(message(write("odd.spv", embedded.words, 10)), Catch::Contains("odd.spv: 10 bytes is not a whole number"));
    const std::uint32_t garbage[8] = { 1, 2, 3, 4, 5, 6, 7, 8 };
    REQUIRE_THAT(message(write("garbage.spv", garbage, sizeof(garbage))), Catch::Contains("garbage.spv: not a SPIR-V module"));
    std::filesystem::remove_all(dir);
}

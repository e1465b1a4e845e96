// Tests of gpu/buffers: round trips through device memory, texel views, images.
#include "gpu/buffers.h"

#include "core/error.h"
#include "test_common.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

using namespace facesketch;

TEST_CASE("buffers: upload and readback round trip, offsets checked")
{
    gpu::Device& d = test::device();
    std::vector<std::uint32_t> data(1000);
    for (std::uint32_t i = 0; i < data.size(); ++i)
        data[i] = i * 2654435761u;
    gpu::Buffer b = gpu::createBuffer(d, data.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    gpu::uploadBuffer(d, b, data.data(), data.size() * 4);
    std::vector<std::uint32_t> back(500);
    gpu::readbackBuffer(d, b, back.data(), 500 * 4, 500 * 4);
    REQUIRE(std::equal(back.begin(), back.end(), data.begin() + 500));
    REQUIRE_THROWS(gpu::uploadBuffer(d, b, data.data(), 8, b.size - 4));
    gpu::destroyBuffer(d, b);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("buffers: a readback buffer round-trips through a device buffer by copies, and sizes are checked")
{
    gpu::Device& d = test::device();
    std::vector<float> data(256);
    std::iota(data.begin(), data.end(), -100.5f);
    gpu::Buffer device = gpu::createBuffer(d, data.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    gpu::Buffer readback = gpu::createBuffer(d, data.size() * sizeof(float), 0, gpu::MemoryUse::Readback);
    REQUIRE(readback.mapped != nullptr); // host-visible by definition
    REQUIRE(device.size == data.size() * sizeof(float));
    gpu::uploadBuffer(d, device, data.data(), data.size() * sizeof(float));
    gpu::submitAndWait(d, [&](VkCommandBuffer cmd) {
        VkBufferCopy region { 0, 0, device.size };
        vkCmdCopyBuffer(cmd, device.buffer, readback.buffer, 1, &region);
    });
    std::vector<float> back(data.size(), 0.0f);
    gpu::readbackBuffer(d, readback, back.data(), back.size() * sizeof(float));
    REQUIRE(back == data);
    // An upload at an offset changes only what it covers.
    const float patch[2] = { 7.0f, 8.0f };
    gpu::uploadBuffer(d, device, patch, sizeof(patch), 10 * sizeof(float));
    gpu::readbackBuffer(d, device, back.data(), back.size() * sizeof(float));
    REQUIRE(back[9] == data[9]);
    REQUIRE(back[10] == 7.0f);
    REQUIRE(back[11] == 8.0f);
    REQUIRE(back[12] == data[12]);
    REQUIRE_THROWS_WITH(gpu::readbackBuffer(d, device, back.data(), 8, device.size - 4), Catch::Contains("exceed the buffer's 1024"));
    REQUIRE_THROWS_WITH(gpu::createBuffer(d, 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT), Catch::Contains("size must be positive"));
    gpu::destroyBuffer(d, readback);
    gpu::destroyBuffer(d, device);
    REQUIRE(device.buffer == VK_NULL_HANDLE); // destroy resets the struct
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("buffers: a texel view must cover whole texels")
{
    gpu::Device& d = test::device();
    gpu::Buffer buffer = gpu::createBuffer(d, 20, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    REQUIRE_THROWS_WITH(
        gpu::createTexelView(d, buffer, VK_FORMAT_R32G32B32A32_UINT), Catch::Contains("20 bytes is not a whole number of 16-byte texels"));
    REQUIRE_THROWS_WITH(gpu::createTexelView(d, buffer, VK_FORMAT_R8G8B8A8_UINT), Catch::Contains("is not one of the texel formats"));
    gpu::TexelView view = gpu::createTexelView(d, buffer, VK_FORMAT_R32_UINT);
    REQUIRE(view.elements == 5);
    gpu::destroyTexelView(d, view);
    gpu::destroyBuffer(d, buffer);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("buffers: texel views count texels of each accepted format and refuse the others")
{
    gpu::Device& d = test::device();
    gpu::Buffer buffer = gpu::createBuffer(d, 64, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    const std::pair<VkFormat, VkDeviceSize> accepted[] = { { VK_FORMAT_R32_UINT, 16 }, { VK_FORMAT_R32G32_UINT, 8 },
        { VK_FORMAT_R32G32B32A32_UINT, 4 }, { VK_FORMAT_R32G32B32A32_SFLOAT, 4 }, { VK_FORMAT_R8G8B8A8_UNORM, 16 } };
    for (const auto& [format, elements] : accepted) {
        gpu::TexelView view = gpu::createTexelView(d, buffer, format);
        REQUIRE(view.view != VK_NULL_HANDLE);
        REQUIRE(view.format == format);
        REQUIRE(view.elements == elements);
        gpu::destroyTexelView(d, view);
        REQUIRE(view.view == VK_NULL_HANDLE);
    }
    for (const VkFormat refused : { VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16G16_UINT, VK_FORMAT_R32G32B32_UINT, VK_FORMAT_R8_UINT })
        REQUIRE_THROWS_WITH(gpu::createTexelView(d, buffer, refused), Catch::Contains("is not one of the texel formats"));
    gpu::destroyBuffer(d, buffer);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("buffers: memory types are chosen by required and preferred flags, and a missing one is an error")
{
    gpu::Device& d = test::device();
    const std::uint32_t all = (1u << d.memory.memoryTypeCount) - 1;
    const std::uint32_t local = gpu::chooseMemoryType(d, all, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    REQUIRE(local < d.memory.memoryTypeCount);
    REQUIRE((d.memory.memoryTypes[local].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) != 0);
    const std::uint32_t visible = gpu::chooseMemoryType(d, all, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    REQUIRE((d.memory.memoryTypes[visible].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) != 0);
    // Only the types allowed by the bits are considered: none allowed, none found.
    REQUIRE_THROWS_WITH(gpu::chooseMemoryType(d, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0), Catch::Contains("no Vulkan memory type"));
}

TEST_CASE("buffers: an image is created with its size, format and view, and destroyed cleanly")
{
    gpu::Device& d = test::device();
    gpu::Image image = gpu::createImage(d, 40, 30, VK_FORMAT_R8G8B8A8_UNORM,
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    REQUIRE(image.image != VK_NULL_HANDLE);
    REQUIRE(image.view != VK_NULL_HANDLE);
    REQUIRE(image.width == 40);
    REQUIRE(image.height == 30);
    REQUIRE(image.format == VK_FORMAT_R8G8B8A8_UNORM);
    gpu::destroyImage(d, image);
    REQUIRE(image.image == VK_NULL_HANDLE);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("submitAndWait: an exception while recording is passed on and nothing recorded runs")
{
    gpu::Device& d = test::device();
    gpu::Buffer b = gpu::createBuffer(d, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    const std::vector<std::uint32_t> zeros(16, 0u);
    gpu::uploadBuffer(d, b, zeros.data(), 64);
    for (int i = 0; i < 3; ++i)
        REQUIRE_THROWS_WITH(gpu::submitAndWait(d,
                                [&](VkCommandBuffer cmd) {
                                    vkCmdFillBuffer(cmd, b.buffer, 0, 64, 0xdeadbeefu);
                                    fail("recording stopped half way");
                                }),
            Catch::Contains("recording stopped half way"));
    std::vector<std::uint32_t> back(16, 1u);
    gpu::readbackBuffer(d, b, back.data(), 64);
    REQUIRE(back == zeros);
    // The device goes on working.
    gpu::submitAndWait(d, [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, b.buffer, 0, 64, 7u); });
    gpu::readbackBuffer(d, b, back.data(), 64);
    REQUIRE(back == std::vector<std::uint32_t>(16, 7u));
    gpu::destroyBuffer(d, b);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

#include "gpu/device.h"
#include "gpu/buffers.h"
#include "test_common.h"

#include <cstdio>

using namespace facesketch;

TEST_CASE("device: headless device with the validation layer active")
{
    gpu::Device& d = test::device();
    std::printf(
        "device: %s (type %d), validation %s\n", d.name.c_str(), static_cast<int>(d.properties.deviceType), d.validation ? "on" : "off");
    REQUIRE(d.device != VK_NULL_HANDLE);
    REQUIRE(d.validation);
    REQUIRE(d.messenger != VK_NULL_HANDLE);
    REQUIRE(d.pushDescriptorSet != nullptr);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("device: the validation layer reports an invalid call, so silence means something")
{
    gpu::Device& d = test::device();
    const std::uint64_t before = gpu::validationMessageCount();
    // VUID-VkBufferCreateInfo-usage-requiredbitmask: usage must not be 0.
    auto info = gpu::makeStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = 64;
    info.usage = 0;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(d.device, &info, nullptr, &buffer) == VK_SUCCESS)
        vkDestroyBuffer(d.device, buffer, nullptr);
    REQUIRE(gpu::validationMessageCount() > before);
    test::validationBaseline() = gpu::validationMessageCount(); // provoked on purpose
}

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

#include "gpu/device.h"
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

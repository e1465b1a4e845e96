#include "gpu/device.h"
#include "test_common.h"

#include <cfenv>
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

TEST_CASE("device: instance, physical device and device made in three steps share the instance")
{
    fedisableexcept(FE_ALL_EXCEPT); // Mesa's rasteriser set-up divides by zero (see test::device)
    gpu::Instance instance = gpu::createInstance({ .validation = true, .requireValidation = true, .extensions = {} });
    REQUIRE(instance.instance != VK_NULL_HANDLE);
    REQUIRE(instance.validation);
    REQUIRE(instance.apiVersion >= VK_API_VERSION_1_2);
    const gpu::PhysicalDeviceChoice choice = gpu::choosePhysicalDevice(instance);
    REQUIRE(choice.physical != VK_NULL_HANDLE);
    gpu::Device d = gpu::createDevice(instance, choice);
    REQUIRE(d.instance == instance.instance);
    REQUIRE_FALSE(d.ownsInstance);
    REQUIRE(d.queueFamily == choice.queueFamily);
    REQUIRE(d.pushDescriptorSet != nullptr);
    REQUIRE_FALSE(d.swapchain);
    // lavapipe and every Vulkan 1.3 driver offer dynamic rendering; begin and end come together.
    if (d.properties.apiVersion >= VK_API_VERSION_1_3 && instance.apiVersion >= VK_API_VERSION_1_3)
        REQUIRE(d.beginRendering != nullptr);
    REQUIRE((d.beginRendering == nullptr) == (d.endRendering == nullptr));
    gpu::destroyDevice(d);
    REQUIRE(d.device == VK_NULL_HANDLE);
    gpu::destroyInstance(instance);
    REQUIRE(instance.instance == VK_NULL_HANDLE);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("device: a missing instance extension is an error naming it")
{
    REQUIRE_THROWS_WITH(
        gpu::createInstance({ .validation = false, .requireValidation = false, .extensions = { "VK_FACESKETCH_no_such_extension" } }),
        Catch::Contains("VK_FACESKETCH_no_such_extension"));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("device: the one-call device owns its instance and enables no swapchain")
{
    gpu::Device& d = test::device();
    REQUIRE(d.ownsInstance);
    REQUIRE_FALSE(d.swapchain);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

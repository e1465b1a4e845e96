#include "gpu/device.h"

#include "core/error.h"

#include <algorithm>
#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#include <link.h>
#endif
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace facesketch::gpu {

namespace {

std::atomic<std::uint64_t> validationMessages { 0 };

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void*)
{
    const bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    validationMessages.fetch_add(1);
    std::fprintf(stderr, "vulkan validation %s: %s\n", error ? "ERROR" : "WARNING", data->pMessage);
    return VK_FALSE;
}

bool envFlag(const char* name)
{
    const char* value = std::getenv(name);
    return value && *value && std::strcmp(value, "0") != 0;
}

bool hasLayer(const char* name)
{
    std::uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool hasInstanceExtension(const char* name)
{
    std::uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data());
    return std::any_of(
        extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

int deviceRank(const VkPhysicalDeviceProperties& p)
{
    switch (p.deviceType) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return 1;
    default:
        return 0;
    }
}

// The first queue family that does graphics and compute (the spec guarantees transfer then).
std::int64_t universalQueueFamily(VkPhysicalDevice physical)
{
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    for (std::uint32_t i = 0; i < count; ++i)
        if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT))
            return i;
    return -1;
}

VkPhysicalDevice choosePhysicalDevice(VkInstance instance)
{
    std::uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));

    std::vector<VkPhysicalDevice> usable;
    std::string names;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        names += cat(names.empty() ? "" : ", ", usable.size(), ": ", p.deviceName);
        if (universalQueueFamily(d) >= 0 && p.apiVersion >= VK_API_VERSION_1_2)
            usable.push_back(d);
    }
    if (usable.empty())
        fail("no Vulkan 1.2 device with a graphics+compute queue (is mesa-vulkan-drivers installed? "
             "tools/setup-debian.sh installs it); devices seen: [",
            names, "]");

    if (const char* want = std::getenv("FACESKETCH_DEVICE"); want && *want) {
        char* end = nullptr;
        const long index = std::strtol(want, &end, 10);
        if (*end == '\0') {
            if (index < 0 || index >= static_cast<long>(usable.size()))
                fail("FACESKETCH_DEVICE=", want, ": no such device index; usable devices: [", names, "]");
            return usable[index];
        }
        for (VkPhysicalDevice d : usable) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(d, &p);
            if (std::strstr(p.deviceName, want))
                return d;
        }
        fail("FACESKETCH_DEVICE=", want, ": matches no usable device; usable devices: [", names, "]");
    }

    return *std::max_element(usable.begin(), usable.end(), [](VkPhysicalDevice a, VkPhysicalDevice b) {
        VkPhysicalDeviceProperties pa, pb;
        vkGetPhysicalDeviceProperties(a, &pa);
        vkGetPhysicalDeviceProperties(b, &pb);
        return deviceRank(pa) < deviceRank(pb);
    });
}

#if defined(__SANITIZE_ADDRESS__)
// The Vulkan loader unloads drivers and layers at vkDestroyInstance, and LeakSanitizer cannot
// name the module of an allocation made by an unloaded library, so tools/lsan.supp could not
// suppress the driver's process-lifetime allocations. Sanitizer builds pin every loaded Vulkan
// driver and layer (and LLVM, lavapipe's JIT) until exit.
void pinVulkanLibraries()
{
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void*) {
            const char* name = info->dlpi_name;
            if (name && (std::strstr(name, "libvulkan_") || std::strstr(name, "libVkLayer") || std::strstr(name, "libLLVM")))
                dlopen(name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
            return 0;
        },
        nullptr);
}
#endif

} // namespace

std::uint64_t validationMessageCount()
{
    return validationMessages.load();
}

Device createDevice(const DeviceOptions& options)
{
    Device d;
#ifndef NDEBUG
    const bool debugBuild = true;
#else
    const bool debugBuild = false;
#endif
    const char* layerName = "VK_LAYER_KHRONOS_validation";
    const bool wantValidation = options.validation || options.requireValidation || envFlag("FACESKETCH_VALIDATION") || debugBuild;
    d.validation = wantValidation && hasLayer(layerName) && hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (wantValidation && !d.validation && (options.requireValidation || envFlag("FACESKETCH_VALIDATION")))
        fail("Vulkan validation requested but ", layerName,
            " or VK_EXT_debug_utils is missing (install vulkan-validationlayers: tools/setup-debian.sh)");

    auto app = makeStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "FaceSketch";
    app.pEngineName = "FaceSketch";
    app.apiVersion = VK_API_VERSION_1_2;

    std::vector<const char*> layers, extensions;
    auto messengerInfo = makeStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT
        | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = onDebugMessage;

    auto instanceInfo = makeStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    instanceInfo.pApplicationInfo = &app;
    if (d.validation) {
        layers.push_back(layerName);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        instanceInfo.pNext = &messengerInfo; // also reports problems during instance creation
    }
    instanceInfo.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    instanceInfo.ppEnabledLayerNames = layers.data();
    instanceInfo.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    instanceInfo.ppEnabledExtensionNames = extensions.data();
    if (VkResult r = vkCreateInstance(&instanceInfo, nullptr, &d.instance); r != VK_SUCCESS)
        gpuFail("creating the Vulkan instance (vkCreateInstance; is a Vulkan driver installed? tools/setup-debian.sh)", r);

    if (d.validation) {
        auto create
            = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(d.instance, "vkCreateDebugUtilsMessengerEXT"));
        VK_CHECK(create(d.instance, &messengerInfo, nullptr, &d.messenger));
    }

    try {
        d.physical = choosePhysicalDevice(d.instance);
    } catch (...) {
        destroyDevice(d);
        throw;
    }
    vkGetPhysicalDeviceProperties(d.physical, &d.properties);
    vkGetPhysicalDeviceMemoryProperties(d.physical, &d.memory);
    d.name = d.properties.deviceName;
    d.queueFamily = static_cast<std::uint32_t>(universalQueueFamily(d.physical));

    std::uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &familyCount, families.data());
    d.timestamps = families[d.queueFamily].timestampValidBits > 0 && d.properties.limits.timestampPeriod > 0;

    VkPhysicalDeviceFeatures available;
    vkGetPhysicalDeviceFeatures(d.physical, &available);
    VkPhysicalDeviceFeatures enabled {};
    enabled.largePoints = available.largePoints;
    enabled.wideLines = available.wideLines;
    enabled.fillModeNonSolid = available.fillModeNonSolid;
    d.largePoints = available.largePoints;

    const float priority = 1.0f;
    auto queueInfo = makeStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queueInfo.queueFamilyIndex = d.queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    std::uint32_t extensionCount = 0;
    vkEnumerateDeviceExtensionProperties(d.physical, nullptr, &extensionCount, nullptr);
    std::vector<VkExtensionProperties> deviceExtensions(extensionCount);
    vkEnumerateDeviceExtensionProperties(d.physical, nullptr, &extensionCount, deviceExtensions.data());
    const char* pushDescriptor = VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
    if (std::none_of(deviceExtensions.begin(), deviceExtensions.end(),
            [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, pushDescriptor) == 0; })) {
        const std::string name = d.name;
        destroyDevice(d);
        fail("Vulkan device ", name, " lacks ", pushDescriptor);
    }

    auto deviceInfo = makeStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    deviceInfo.enabledExtensionCount = 1;
    deviceInfo.ppEnabledExtensionNames = &pushDescriptor;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.pEnabledFeatures = &enabled;
    VK_CHECK(vkCreateDevice(d.physical, &deviceInfo, nullptr, &d.device));
    vkGetDeviceQueue(d.device, d.queueFamily, 0, &d.queue);
    d.pushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(d.device, "vkCmdPushDescriptorSetKHR"));

    auto poolInfo = makeStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = d.queueFamily;
    VK_CHECK(vkCreateCommandPool(d.device, &poolInfo, nullptr, &d.commandPool));
#if defined(__SANITIZE_ADDRESS__)
    pinVulkanLibraries();
#endif
    return d;
}

void destroyDevice(Device& d)
{
    if (d.commandPool)
        vkDestroyCommandPool(d.device, d.commandPool, nullptr);
    if (d.device)
        vkDestroyDevice(d.device, nullptr);
    if (d.messenger) {
        auto destroy
            = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(d.instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(d.instance, d.messenger, nullptr);
    }
    if (d.instance)
        vkDestroyInstance(d.instance, nullptr);
    d = Device {};
}

VkCommandBuffer beginOneShot(Device& d)
{
    auto info = makeStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    info.commandPool = d.commandPool;
    info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    info.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(d.device, &info, &cmd));
    auto begin = makeStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    return cmd;
}

void endOneShotAndWait(Device& d, VkCommandBuffer cmd)
{
    VK_CHECK(vkEndCommandBuffer(cmd));
    auto fenceInfo = makeStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    VkFence fence;
    VK_CHECK(vkCreateFence(d.device, &fenceInfo, nullptr, &fence));
    auto submit = makeStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    const VkResult submitted = vkQueueSubmit(d.queue, 1, &submit, fence);
    const VkResult waited = submitted == VK_SUCCESS ? vkWaitForFences(d.device, 1, &fence, VK_TRUE, UINT64_MAX) : submitted;
    vkDestroyFence(d.device, fence, nullptr);
    vkFreeCommandBuffers(d.device, d.commandPool, 1, &cmd);
    if (submitted != VK_SUCCESS)
        gpuFail("submitting GPU work (vkQueueSubmit)", submitted);
    if (waited != VK_SUCCESS)
        gpuFail("waiting for GPU work to finish (vkWaitForFences)", waited);
}

} // namespace facesketch::gpu

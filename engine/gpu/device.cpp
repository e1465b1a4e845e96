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

bool hasDeviceExtension(VkPhysicalDevice physical, const char* name)
{
    std::uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data());
    return std::any_of(
        extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// The first queue family that does graphics and compute (the spec guarantees transfer then) and,
// with a surface, presents to it.
std::int64_t universalQueueFamily(VkPhysicalDevice physical, VkSurfaceKHR surface)
{
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    for (std::uint32_t i = 0; i < count; ++i) {
        if (!(families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) || !(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT))
            continue;
        if (surface) {
            VkBool32 present = VK_FALSE;
            if (vkGetPhysicalDeviceSurfaceSupportKHR(physical, i, surface, &present) != VK_SUCCESS || !present)
                continue;
        }
        return i;
    }
    return -1;
}

} // namespace

PhysicalDeviceChoice choosePhysicalDevice(const Instance& instance, VkSurfaceKHR surface)
{
    std::uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance.instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance.instance, &count, devices.data()));

    std::vector<VkPhysicalDevice> usable;
    std::string names;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        names += cat(names.empty() ? "" : ", ", usable.size(), ": ", p.deviceName);
        if (universalQueueFamily(d, surface) >= 0 && p.apiVersion >= VK_API_VERSION_1_2
            && (!surface || hasDeviceExtension(d, VK_KHR_SWAPCHAIN_EXTENSION_NAME)))
            usable.push_back(d);
    }
    const char* what = surface ? "a graphics+compute queue that presents to the window" : "a graphics+compute queue";
    if (usable.empty())
        fail("no Vulkan 1.2 device with ", what,
            " (is mesa-vulkan-drivers installed? "
            "tools/setup-debian.sh installs it); devices seen: [",
            names, "]");

    auto choice = [&](VkPhysicalDevice d) {
        return PhysicalDeviceChoice { d, static_cast<std::uint32_t>(universalQueueFamily(d, surface)) };
    };
    if (const char* want = std::getenv("FACESKETCH_DEVICE"); want && *want) {
        char* end = nullptr;
        const long index = std::strtol(want, &end, 10);
        if (*end == '\0') {
            if (index < 0 || index >= static_cast<long>(usable.size()))
                fail("FACESKETCH_DEVICE=", want, ": no such device index; usable devices: [", names, "]");
            return choice(usable[index]);
        }
        for (VkPhysicalDevice d : usable) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(d, &p);
            if (std::strstr(p.deviceName, want))
                return choice(d);
        }
        fail("FACESKETCH_DEVICE=", want, ": matches no usable device; usable devices: [", names, "]");
    }

    return choice(*std::max_element(usable.begin(), usable.end(), [](VkPhysicalDevice a, VkPhysicalDevice b) {
        VkPhysicalDeviceProperties pa, pb;
        vkGetPhysicalDeviceProperties(a, &pa);
        vkGetPhysicalDeviceProperties(b, &pb);
        return deviceRank(pa) < deviceRank(pb);
    }));
}

namespace {

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

Instance createInstance(const InstanceOptions& options)
{
    Instance result;
#ifndef NDEBUG
    const bool debugBuild = true;
#else
    const bool debugBuild = false;
#endif
    const char* layerName = "VK_LAYER_KHRONOS_validation";
    const bool wantValidation = options.validation || options.requireValidation || envFlag("FACESKETCH_VALIDATION") || debugBuild;
    result.validation = wantValidation && hasLayer(layerName) && hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (wantValidation && !result.validation && (options.requireValidation || envFlag("FACESKETCH_VALIDATION")))
        fail("Vulkan validation requested but ", layerName,
            " or VK_EXT_debug_utils is missing (install vulkan-validationlayers: tools/setup-debian.sh)");
    for (const char* extension : options.extensions)
        if (!hasInstanceExtension(extension))
            fail("the Vulkan instance lacks the extension ", extension, " (needed by the window; is a Vulkan driver for it installed?)");

    // 1.3 when the loader has it, so that a 1.3 device offers dynamic rendering in core.
    std::uint32_t loaderVersion = VK_API_VERSION_1_0;
    vkEnumerateInstanceVersion(&loaderVersion);
    result.apiVersion = loaderVersion >= VK_API_VERSION_1_3 ? VK_API_VERSION_1_3 : VK_API_VERSION_1_2;

    auto app = makeStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "FaceSketch";
    app.pEngineName = "FaceSketch";
    app.apiVersion = result.apiVersion;

    std::vector<const char*> layers, extensions = options.extensions;
    auto messengerInfo = makeStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT
        | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = onDebugMessage;

    auto instanceInfo = makeStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    instanceInfo.pApplicationInfo = &app;
    if (result.validation) {
        layers.push_back(layerName);
        if (std::none_of(
                extensions.begin(), extensions.end(), [](const char* e) { return std::strcmp(e, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) == 0; }))
            extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        instanceInfo.pNext = &messengerInfo; // also reports problems during instance creation
    }
    instanceInfo.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    instanceInfo.ppEnabledLayerNames = layers.data();
    instanceInfo.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    instanceInfo.ppEnabledExtensionNames = extensions.data();
    if (VkResult r = vkCreateInstance(&instanceInfo, nullptr, &result.instance); r != VK_SUCCESS)
        gpuFail("creating the Vulkan instance (vkCreateInstance; is a Vulkan driver installed? tools/setup-debian.sh)", r);

    if (result.validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(result.instance, "vkCreateDebugUtilsMessengerEXT"));
        if (VkResult r = create(result.instance, &messengerInfo, nullptr, &result.messenger); r != VK_SUCCESS) {
            vkDestroyInstance(result.instance, nullptr);
            gpuFail("creating the validation messenger (vkCreateDebugUtilsMessengerEXT)", r);
        }
    }
    return result;
}

void destroyInstance(Instance& instance)
{
    if (instance.messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance.instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance.instance, instance.messenger, nullptr);
    }
    if (instance.instance)
        vkDestroyInstance(instance.instance, nullptr);
    instance = Instance {};
}

Device createDevice(const Instance& instance, const PhysicalDeviceChoice& choice, const LogicalDeviceOptions& options)
{
    Device d;
    d.instance = instance.instance;
    d.validation = instance.validation;
    d.physical = choice.physical;
    d.queueFamily = choice.queueFamily;
    vkGetPhysicalDeviceProperties(d.physical, &d.properties);
    vkGetPhysicalDeviceMemoryProperties(d.physical, &d.memory);
    d.name = d.properties.deviceName;

    std::uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &familyCount, families.data());
    if (d.queueFamily >= familyCount)
        fail("createDevice: queue family ", d.queueFamily, " does not exist on ", d.name);
    d.timestamps = families[d.queueFamily].timestampValidBits > 0 && d.properties.limits.timestampPeriod > 0;

    std::vector<const char*> extensions { VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME };
    if (!hasDeviceExtension(d.physical, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
        fail("Vulkan device ", d.name, " lacks ", VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    if (options.swapchain) {
        if (!hasDeviceExtension(d.physical, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
            fail("Vulkan device ", d.name, " lacks ", VK_KHR_SWAPCHAIN_EXTENSION_NAME, " (it cannot show a window)");
        extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
        d.swapchain = true;
    }
    // Dynamic rendering: core in a 1.3 device on a 1.3 instance, else the KHR extension.
    const bool core13 = instance.apiVersion >= VK_API_VERSION_1_3 && d.properties.apiVersion >= VK_API_VERSION_1_3;
    const bool dynamicRenderingExtension = !core13 && hasDeviceExtension(d.physical, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
    if (dynamicRenderingExtension)
        extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);

    auto dynamicRendering
        = makeStruct<VkPhysicalDeviceDynamicRenderingFeaturesKHR>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES_KHR);
    auto available = makeStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    if (core13 || dynamicRenderingExtension)
        available.pNext = &dynamicRendering;
    vkGetPhysicalDeviceFeatures2(d.physical, &available);
    const bool useDynamicRendering = dynamicRendering.dynamicRendering == VK_TRUE;

    auto enabled = makeStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    enabled.features.largePoints = available.features.largePoints;
    enabled.features.wideLines = available.features.wideLines;
    enabled.features.fillModeNonSolid = available.features.fillModeNonSolid;
    d.largePoints = available.features.largePoints;
    d.wideLines = available.features.wideLines;
    auto enabledDynamicRendering
        = makeStruct<VkPhysicalDeviceDynamicRenderingFeaturesKHR>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES_KHR);
    enabledDynamicRendering.dynamicRendering = VK_TRUE;
    if (useDynamicRendering)
        enabled.pNext = &enabledDynamicRendering;
    else if (dynamicRenderingExtension)
        extensions.pop_back();

    const float priority = 1.0f;
    auto queueInfo = makeStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queueInfo.queueFamilyIndex = d.queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    auto deviceInfo = makeStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    deviceInfo.pNext = &enabled;
    deviceInfo.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    deviceInfo.ppEnabledExtensionNames = extensions.data();
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    if (VkResult r = vkCreateDevice(d.physical, &deviceInfo, nullptr, &d.device); r != VK_SUCCESS)
        gpuFail(cat("creating the Vulkan device on ", d.name, " (vkCreateDevice)"), r);
    vkGetDeviceQueue(d.device, d.queueFamily, 0, &d.queue);
    d.pushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(d.device, "vkCmdPushDescriptorSetKHR"));
    if (useDynamicRendering) {
        d.beginRendering = reinterpret_cast<PFN_vkCmdBeginRenderingKHR>(
            vkGetDeviceProcAddr(d.device, core13 ? "vkCmdBeginRendering" : "vkCmdBeginRenderingKHR"));
        d.endRendering = reinterpret_cast<PFN_vkCmdEndRenderingKHR>(
            vkGetDeviceProcAddr(d.device, core13 ? "vkCmdEndRendering" : "vkCmdEndRenderingKHR"));
    }

    auto poolInfo = makeStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = d.queueFamily;
    VK_CHECK(vkCreateCommandPool(d.device, &poolInfo, nullptr, &d.commandPool));
#if defined(__SANITIZE_ADDRESS__)
    pinVulkanLibraries();
#endif
    return d;
}

Device createDevice(const DeviceOptions& options)
{
    Instance instance
        = createInstance({ .validation = options.validation, .requireValidation = options.requireValidation, .extensions = {} });
    try {
        Device d = createDevice(instance, choosePhysicalDevice(instance));
        d.messenger = instance.messenger;
        d.ownsInstance = true;
        return d;
    } catch (...) {
        destroyInstance(instance);
        throw;
    }
}

void destroyDevice(Device& d)
{
    if (d.commandPool)
        vkDestroyCommandPool(d.device, d.commandPool, nullptr);
    if (d.device)
        vkDestroyDevice(d.device, nullptr);
    if (d.ownsInstance) {
        Instance instance { d.instance, d.messenger, 0, d.validation };
        destroyInstance(instance);
    }
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

void abandonOneShot(Device& d, VkCommandBuffer cmd)
{
    // Never submitted, so not pending: a buffer still recording may be freed as it is.
    vkFreeCommandBuffers(d.device, d.commandPool, 1, &cmd);
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

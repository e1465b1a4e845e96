#pragma once
// Vulkan instance and device without any window. Prefers a real GPU (discrete, then integrated),
// falls back to a CPU implementation (Mesa lavapipe). FACESKETCH_DEVICE=<index or name
// substring> overrides the choice. FACESKETCH_VALIDATION=1 (set by every test) or a debug build
// enables VK_LAYER_KHRONOS_validation; each message it reports is printed and counted, and the
// test main fails the test that caused it.
//
// Device creation comes in three steps, as a windowed app needs them (instance, then the app's
// surface, then a physical device that presents to it, then the device), or in one call for
// headless work (createDevice(DeviceOptions), ScopedDevice).
//
// Lifetime: plain structs with createX/destroyX pairs, destroyed in reverse order of creation.

#include "gpu/error.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace facesketch::gpu {

/// A zero-initialised Vulkan struct with its sType set: `auto info = makeStruct<VkBufferCreateInfo>(
/// VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);` (brace-initialising only sType trips -Wextra).
template <typename T> T makeStruct(VkStructureType type)
{
    T value {};
    value.sType = type;
    return value;
}

/// What the instance enables. A windowed app passes the surface extensions its window library
/// needs (glfwGetRequiredInstanceExtensions); headless code passes none.
struct InstanceOptions {
    bool validation = false;        ///< also on when FACESKETCH_VALIDATION=1 or in a debug build
    bool requireValidation = false; ///< throw Error if the validation layer is missing
    /// Extra instance extensions (e.g. VK_KHR_surface, VK_KHR_xcb_surface); each must exist,
    /// else Error names it. The pointers are only read during createInstance.
    std::vector<const char*> extensions;
};

/// The Vulkan instance and, with validation, the debug messenger that counts its messages.
struct Instance {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    std::uint32_t apiVersion = 0; ///< the version asked for: 1.3 when the loader has it, else 1.2
    bool validation = false;      ///< the validation layer is active
};

/// Creates the instance (and the messenger when validation is on). Throws Error when validation
/// is required but missing or an extension is missing; GpuError when vkCreateInstance fails.
Instance createInstance(const InstanceOptions& options = {});
/// Destroys messenger and instance; every device and surface made from it must be gone.
void destroyInstance(Instance& instance);

/// A physical device and the queue family FaceSketch uses on it.
struct PhysicalDeviceChoice {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    std::uint32_t queueFamily = 0; ///< does graphics + compute (+ present to the surface, if one was given)
};

/// Picks a Vulkan 1.2 device with one queue family that does graphics and compute and, when
/// `surface` is not VK_NULL_HANDLE, presents to it (vkGetPhysicalDeviceSurfaceSupportKHR) and
/// has VK_KHR_swapchain. Prefers a discrete GPU, then integrated, virtual, CPU (lavapipe);
/// FACESKETCH_DEVICE=<index or name substring> overrides among the usable ones. Throws Error
/// naming every device seen when none is usable.
PhysicalDeviceChoice choosePhysicalDevice(const Instance& instance, VkSurfaceKHR surface = VK_NULL_HANDLE);

/// What the logical device enables beyond the always-on set (VK_KHR_push_descriptor, large
/// points, wide lines, non-solid fill when available; dynamic rendering when available).
struct LogicalDeviceOptions {
    bool swapchain = false; ///< enable VK_KHR_swapchain (throws Error if the device lacks it)
};

/// Options of the one-call headless device.
struct DeviceOptions {
    bool validation = false;        ///< also on when FACESKETCH_VALIDATION=1 or in a debug build
    bool requireValidation = false; ///< throw Error if the validation layer is missing
};

struct Device {
    VkInstance instance = VK_NULL_HANDLE; ///< the instance the device was made from
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE; ///< one queue that does graphics, compute and transfer (and present, if asked)
    std::uint32_t queueFamily = 0;
    VkCommandPool commandPool = VK_NULL_HANDLE; ///< for one-shot command buffers on `queue`
    VkPhysicalDeviceProperties properties {};
    VkPhysicalDeviceMemoryProperties memory {};
    bool validation = false; ///< the validation layer is active
    bool timestamps = false; ///< the queue supports timestamp queries
    bool largePoints = false;
    bool wideLines = false;
    bool swapchain = false; ///< VK_KHR_swapchain is enabled
    /// vkCmdPushDescriptorSetKHR (VK_KHR_push_descriptor is required: every desktop driver and
    /// lavapipe have it, and it spares per-dispatch descriptor pools).
    PFN_vkCmdPushDescriptorSetKHR pushDescriptorSet = nullptr;
    /// vkCmdBeginRendering / vkCmdEndRendering (Vulkan 1.3 core or VK_KHR_dynamic_rendering);
    /// null when the device has neither, and then only render passes can be drawn into.
    PFN_vkCmdBeginRenderingKHR beginRendering = nullptr;
    PFN_vkCmdEndRenderingKHR endRendering = nullptr;
    std::string name;          ///< e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    bool ownsInstance = false; ///< destroyDevice also destroys the instance (the one-call createDevice)
};

/// The logical device, its queue and one-shot command pool on `choice`, made from `instance`
/// (which must outlive it: destroyDevice leaves it alone). The three steps for a window:
///
///   gpu::Instance instance = gpu::createInstance({ .extensions = glfwExtensions });
///   glfwCreateWindowSurface(instance.instance, window, nullptr, &surface);
///   gpu::Device device = gpu::createDevice(instance, gpu::choosePhysicalDevice(instance, surface), { .swapchain = true });
///   ... gpu::destroyDevice(device); vkDestroySurfaceKHR(instance.instance, surface, nullptr); gpu::destroyInstance(instance);
Device createDevice(const Instance& instance, const PhysicalDeviceChoice& choice, const LogicalDeviceOptions& options = {});

/// Headless, in one call: createInstance, choosePhysicalDevice (no surface) and createDevice;
/// the device owns its instance. Throws Error when no device with a graphics+compute queue exists.
Device createDevice(const DeviceOptions& options = {});
/// Destroys the device (and its instance when it owns it).
void destroyDevice(Device& device);

/// Owns a Device for a scope and destroys it on the way out, exceptions included: for code that
/// uses one device from start to end (commands, benchmarks, the test fixture).
class ScopedDevice {
public:
    explicit ScopedDevice(const DeviceOptions& options = {})
        : device_(createDevice(options))
    {
    }
    ~ScopedDevice() { destroyDevice(device_); }
    ScopedDevice(const ScopedDevice&) = delete;
    ScopedDevice& operator=(const ScopedDevice&) = delete;
    Device& operator*() { return device_; }
    Device* operator->() { return &device_; }

private:
    Device device_;
};

/// Number of validation messages (warnings and errors) reported since the process started.
std::uint64_t validationMessageCount();

/// Records commands through `record` into a one-shot command buffer, submits it and waits.
/// Throws GpuError when the submission or the wait fails (a lost device); an exception from
/// `record` is passed on unsubmitted. Either way the command buffer is freed first.
template <typename F> void submitAndWait(Device& device, F&& record);

// Implementation details of submitAndWait.
VkCommandBuffer beginOneShot(Device& device);
void endOneShotAndWait(Device& device, VkCommandBuffer cmd);
void abandonOneShot(Device& device, VkCommandBuffer cmd);

template <typename F> void submitAndWait(Device& device, F&& record)
{
    VkCommandBuffer cmd = beginOneShot(device);
    try {
        record(cmd);
    } catch (...) {
        abandonOneShot(device, cmd);
        throw;
    }
    endOneShotAndWait(device, cmd);
}

} // namespace facesketch::gpu

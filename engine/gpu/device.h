#pragma once
// Vulkan instance and device without any window. Prefers a real GPU (discrete, then integrated),
// falls back to a CPU implementation (Mesa lavapipe). FACESKETCH_DEVICE=<index or name
// substring> overrides the choice. FACESKETCH_VALIDATION=1 (set by every test) or a debug build
// enables VK_LAYER_KHRONOS_validation; each message it reports is printed and counted, and the
// test main fails the test that caused it.
//
// Lifetime: plain structs with createX/destroyX pairs, destroyed in reverse order of creation.

#include "gpu/error.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace facesketch::gpu {

/// A zero-initialised Vulkan struct with its sType set: `auto info = makeStruct<VkBufferCreateInfo>(
/// VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);` (brace-initialising only sType trips -Wextra).
template <typename T> T makeStruct(VkStructureType type)
{
    T value {};
    value.sType = type;
    return value;
}

struct DeviceOptions {
    bool validation = false;        ///< also on when FACESKETCH_VALIDATION=1 or in a debug build
    bool requireValidation = false; ///< throw Error if the validation layer is missing
};

struct Device {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE; ///< one queue that does graphics, compute and transfer
    std::uint32_t queueFamily = 0;
    VkCommandPool commandPool = VK_NULL_HANDLE; ///< for one-shot command buffers on `queue`
    VkPhysicalDeviceProperties properties {};
    VkPhysicalDeviceMemoryProperties memory {};
    bool validation = false; ///< the validation layer is active
    bool timestamps = false; ///< the queue supports timestamp queries
    bool largePoints = false;
    /// vkCmdPushDescriptorSetKHR (VK_KHR_push_descriptor is required: every desktop driver and
    /// lavapipe have it, and it spares per-dispatch descriptor pools).
    PFN_vkCmdPushDescriptorSetKHR pushDescriptorSet = nullptr;
    std::string name; ///< e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
};

/// Creates instance, debug messenger (with validation), device and queue. Throws Error when no
/// device with a graphics+compute queue exists.
Device createDevice(const DeviceOptions& options = {});
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
/// Throws GpuError when the submission or the wait fails (a lost device), having freed the
/// command buffer.
template <typename F> void submitAndWait(Device& device, F&& record);

// Implementation detail of submitAndWait.
VkCommandBuffer beginOneShot(Device& device);
void endOneShotAndWait(Device& device, VkCommandBuffer cmd);

template <typename F> void submitAndWait(Device& device, F&& record)
{
    VkCommandBuffer cmd = beginOneShot(device);
    record(cmd);
    endOneShotAndWait(device, cmd);
}

} // namespace facesketch::gpu

#pragma once
// GPU failures, apart from bad input (core/error.h): a lost device, memory the device does not
// have, a driver that cannot start or lacks a feature. They throw GpuError, a facesketch::Error
// (so one catch still reports every failure) whose message says what failed, the VkResult's
// name and what a user can try: run again, update the driver, pick another device with
// FACESKETCH_DEVICE, use less data. Nothing aborts: an app can report the error and keep its
// document, and a lost device is destroyed and created again by whoever owns it.

#include "core/error.h"

#include <vulkan/vulkan.h>

#include <string>
#include <string_view>

namespace facesketch::gpu {

class GpuError : public Error {
public:
    GpuError(const std::string& message, VkResult result)
        : Error(message)
        , result_(result)
    {
    }
    /// The Vulkan result that reported the failure.
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

/// The enumerator's name ("VK_ERROR_DEVICE_LOST"), or "VkResult(N)" for a code not listed.
std::string vkResultName(VkResult result);

/// What a user can do about `result`, one sentence naming the remedies (FACESKETCH_DEVICE, the
/// driver, less data); a generic one for codes without a specific remedy.
const char* vkResultAdvice(VkResult result);

/// "<what> failed with <name>: <advice>".
std::string gpuFailureMessage(std::string_view what, VkResult result);

/// Throws GpuError(gpuFailureMessage(what, result), result).
[[noreturn]] void gpuFail(std::string_view what, VkResult result);

/// Throws GpuError naming the call, its VkResult and the source line, with the advice; for
/// calls that fail only when the device or driver does (lost device, out of memory), never in
/// a correct program on a working device.
#define VK_CHECK(call)                                                                                                                     \
    do {                                                                                                                                   \
        VkResult vkCheckResult_ = (call);                                                                                                  \
        if (vkCheckResult_ != VK_SUCCESS)                                                                                                  \
            ::facesketch::gpu::vkFailed(#call, vkCheckResult_, __FILE__, __LINE__);                                                        \
    } while (0)

[[noreturn]] void vkFailed(const char* call, VkResult result, const char* file, int line);

} // namespace facesketch::gpu

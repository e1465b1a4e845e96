#include "gpu/error.h"

namespace facesketch::gpu {

std::string vkResultName(VkResult result)
{
    switch (result) {
#define FACESKETCH_RESULT(name)                                                                                                            \
    case name:                                                                                                                             \
        return #name
        FACESKETCH_RESULT(VK_SUCCESS);
        FACESKETCH_RESULT(VK_NOT_READY);
        FACESKETCH_RESULT(VK_TIMEOUT);
        FACESKETCH_RESULT(VK_EVENT_SET);
        FACESKETCH_RESULT(VK_EVENT_RESET);
        FACESKETCH_RESULT(VK_INCOMPLETE);
        FACESKETCH_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY);
        FACESKETCH_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY);
        FACESKETCH_RESULT(VK_ERROR_INITIALIZATION_FAILED);
        FACESKETCH_RESULT(VK_ERROR_DEVICE_LOST);
        FACESKETCH_RESULT(VK_ERROR_MEMORY_MAP_FAILED);
        FACESKETCH_RESULT(VK_ERROR_LAYER_NOT_PRESENT);
        FACESKETCH_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT);
        FACESKETCH_RESULT(VK_ERROR_FEATURE_NOT_PRESENT);
        FACESKETCH_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER);
        FACESKETCH_RESULT(VK_ERROR_TOO_MANY_OBJECTS);
        FACESKETCH_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED);
        FACESKETCH_RESULT(VK_ERROR_FRAGMENTED_POOL);
        FACESKETCH_RESULT(VK_ERROR_UNKNOWN);
        FACESKETCH_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY);
        FACESKETCH_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE);
        FACESKETCH_RESULT(VK_ERROR_FRAGMENTATION);
        FACESKETCH_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS);
        FACESKETCH_RESULT(VK_ERROR_SURFACE_LOST_KHR);
        FACESKETCH_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR);
        FACESKETCH_RESULT(VK_SUBOPTIMAL_KHR);
        FACESKETCH_RESULT(VK_ERROR_OUT_OF_DATE_KHR);
        FACESKETCH_RESULT(VK_ERROR_VALIDATION_FAILED_EXT);
#undef FACESKETCH_RESULT
    default:
        return cat("VkResult(", static_cast<int>(result), ")");
    }
}

const char* vkResultAdvice(VkResult result)
{
    switch (result) {
    case VK_ERROR_DEVICE_LOST:
        return "the GPU stopped responding or its driver reset it, and what it was computing is lost; run again, update the GPU "
               "driver if it happens again, or choose another device with FACESKETCH_DEVICE=<index or name> "
               "(FACESKETCH_DEVICE=llvmpipe computes on the CPU)";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
    case VK_ERROR_OUT_OF_POOL_MEMORY:
    case VK_ERROR_FRAGMENTED_POOL:
    case VK_ERROR_FRAGMENTATION:
    case VK_ERROR_MEMORY_MAP_FAILED:
        return "the GPU has too little free memory for this; use fewer faces or a lower resolution, close other programs using "
               "the GPU, or choose a device with more memory with FACESKETCH_DEVICE=<index or name>";
    case VK_ERROR_OUT_OF_HOST_MEMORY:
        return "the computer ran out of memory; use fewer faces or a lower resolution, or close other programs";
    case VK_ERROR_INITIALIZATION_FAILED:
    case VK_ERROR_INCOMPATIBLE_DRIVER:
        return "the Vulkan driver could not start; install or update it (tools/setup-debian.sh installs Mesa's), or choose "
               "another device with FACESKETCH_DEVICE=<index or name>";
    case VK_ERROR_LAYER_NOT_PRESENT:
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_FEATURE_NOT_PRESENT:
    case VK_ERROR_FORMAT_NOT_SUPPORTED:
    case VK_ERROR_TOO_MANY_OBJECTS:
        return "this device or driver lacks something FaceSketch needs; update the driver, or choose another device with "
               "FACESKETCH_DEVICE=<index or name>";
    default:
        return "an unexpected Vulkan failure; run again, update the GPU driver, or choose another device with "
               "FACESKETCH_DEVICE=<index or name>, and report this message if it persists";
    }
}

std::string gpuFailureMessage(std::string_view what, VkResult result)
{
    return cat(what, " failed with ", vkResultName(result), ": ", vkResultAdvice(result));
}

void gpuFail(std::string_view what, VkResult result)
{
    throw GpuError(gpuFailureMessage(what, result), result);
}

void vkFailed(const char* call, VkResult result, const char* file, int line)
{
    gpuFail(cat(call, " (", file, ":", line, ")"), result);
}

} // namespace facesketch::gpu

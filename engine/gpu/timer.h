#pragma once
// GPU time of recorded work, from timestamp queries (falls back to nothing: check `available`).
// For benchmarks; wall-clock timing of whole operations is core/stopwatch.h.

#include "gpu/device.h"

namespace facesketch::gpu {

struct GpuTimer {
    VkQueryPool pool = VK_NULL_HANDLE;
    double nanosecondsPerTick = 0;
    bool available = false; ///< false when the queue has no timestamp support
};

GpuTimer createGpuTimer(Device& device);
void destroyGpuTimer(Device& device, GpuTimer& timer);
/// Resets the two queries and writes the start timestamp (outside a render pass).
void timerStart(VkCommandBuffer cmd, const GpuTimer& timer);
/// Writes the end timestamp after all previously recorded work completes.
void timerEnd(VkCommandBuffer cmd, const GpuTimer& timer);
/// Milliseconds between start and end of the last submitted recording (waits for results);
/// negative when timestamps are unavailable.
double timerMilliseconds(Device& device, const GpuTimer& timer);

} // namespace facesketch::gpu

#include "gpu/timer.h"

#include <cstdint>

namespace facesketch::gpu {

GpuTimer createGpuTimer(Device& device)
{
    GpuTimer t;
    t.available = device.timestamps;
    if (!t.available)
        return t;
    t.nanosecondsPerTick = device.properties.limits.timestampPeriod;
    auto info = makeStruct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2;
    VK_CHECK(vkCreateQueryPool(device.device, &info, nullptr, &t.pool));
    return t;
}

void destroyGpuTimer(Device& device, GpuTimer& t)
{
    if (t.pool)
        vkDestroyQueryPool(device.device, t.pool, nullptr);
    t = GpuTimer {};
}

void timerStart(VkCommandBuffer cmd, const GpuTimer& t)
{
    if (!t.available)
        return;
    vkCmdResetQueryPool(cmd, t.pool, 0, 2);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, t.pool, 0);
}

void timerEnd(VkCommandBuffer cmd, const GpuTimer& t)
{
    if (t.available)
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, t.pool, 1);
}

double timerMilliseconds(Device& device, const GpuTimer& t)
{
    if (!t.available)
        return -1;
    std::uint64_t ticks[2];
    VK_CHECK(vkGetQueryPoolResults(
        device.device, t.pool, 0, 2, sizeof(ticks), ticks, sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    return static_cast<double>(ticks[1] - ticks[0]) * t.nanosecondsPerTick * 1e-6;
}

} // namespace facesketch::gpu

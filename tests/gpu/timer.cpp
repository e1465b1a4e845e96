// Tests of gpu/timer: GPU milliseconds from timestamp queries.
#include "gpu/timer.h"

#include "gpu/buffers.h"
#include "test_common.h"

#include <algorithm>

using namespace facesketch;

namespace {
// The fastest of three timed submissions of `fills` fills of `buffer`: the machine is shared,
// and the fastest run is the one least disturbed.
double fastestFills(gpu::Device& d, const gpu::GpuTimer& timer, const gpu::Buffer& buffer, int fills)
{
    double fastest = 1e300;
    for (int run = 0; run < 3; ++run) {
        gpu::submitAndWait(d, [&](VkCommandBuffer cmd) {
            gpu::timerStart(cmd, timer);
            for (int k = 0; k < fills; ++k)
                vkCmdFillBuffer(cmd, buffer.buffer, 0, VK_WHOLE_SIZE, static_cast<std::uint32_t>(k));
            gpu::timerEnd(cmd, timer);
        });
        fastest = std::min(fastest, gpu::timerMilliseconds(d, timer));
    }
    return fastest;
}
} // namespace

TEST_CASE("timer: GPU milliseconds are non-negative and grow with the work, or -1 without timestamps")
{
    gpu::Device& d = test::device();
    gpu::GpuTimer timer = gpu::createGpuTimer(d);
    REQUIRE(timer.available == d.timestamps);
    gpu::Buffer buffer = gpu::createBuffer(d, 16u << 20, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const double little = fastestFills(d, timer, buffer, 1), much = fastestFills(d, timer, buffer, 24);
    if (timer.available) {
        INFO("one 16 MB fill " << little << " ms, 24 fills " << much << " ms");
        REQUIRE(timer.nanosecondsPerTick > 0);
        REQUIRE(little >= 0);
        REQUIRE(much > little); // 24 times the bytes written
    } else {
        REQUIRE(little == -1);
        REQUIRE(much == -1);
    }
    gpu::destroyBuffer(d, buffer);
    gpu::destroyGpuTimer(d, timer);
    REQUIRE(timer.pool == VK_NULL_HANDLE);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

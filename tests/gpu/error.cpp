// Tests of gpu/error: GPU failures throw GpuError, a facesketch::Error, with the VkResult's name
// and what a user can try.
#include "gpu/error.h"

#include <catch2/catch.hpp>

using namespace facesketch;

TEST_CASE("gpu error: VkResult names, with unknown codes by number")
{
    REQUIRE(gpu::vkResultName(VK_SUCCESS) == "VK_SUCCESS");
    REQUIRE(gpu::vkResultName(VK_ERROR_DEVICE_LOST) == "VK_ERROR_DEVICE_LOST");
    REQUIRE(gpu::vkResultName(VK_ERROR_OUT_OF_DEVICE_MEMORY) == "VK_ERROR_OUT_OF_DEVICE_MEMORY");
    REQUIRE(gpu::vkResultName(VK_ERROR_OUT_OF_POOL_MEMORY) == "VK_ERROR_OUT_OF_POOL_MEMORY");
    REQUIRE(gpu::vkResultName(static_cast<VkResult>(-12345)) == "VkResult(-12345)");
}

TEST_CASE("gpu error: each failure's message says what failed, the result, and a remedy of its kind")
{
    const std::string lost = gpu::gpuFailureMessage("submitting GPU work (vkQueueSubmit)", VK_ERROR_DEVICE_LOST);
    CHECK_THAT(lost, Catch::StartsWith("submitting GPU work (vkQueueSubmit) failed with VK_ERROR_DEVICE_LOST: "));
    CHECK_THAT(lost, Catch::Contains("driver") && Catch::Contains("FACESKETCH_DEVICE=") && Catch::Contains("run again"));
    const std::string memory = gpu::gpuFailureMessage("allocating 5 bytes", VK_ERROR_OUT_OF_DEVICE_MEMORY);
    CHECK_THAT(
        memory, Catch::Contains("VK_ERROR_OUT_OF_DEVICE_MEMORY") && Catch::Contains("fewer faces") && Catch::Contains("FACESKETCH_DEVICE"));
    CHECK_THAT(gpu::gpuFailureMessage("x", VK_ERROR_OUT_OF_HOST_MEMORY), Catch::Contains("computer ran out of memory"));
    CHECK_THAT(gpu::gpuFailureMessage("x", VK_ERROR_INCOMPATIBLE_DRIVER), Catch::Contains("tools/setup-debian.sh"));
    CHECK_THAT(gpu::gpuFailureMessage("x", VK_ERROR_EXTENSION_NOT_PRESENT), Catch::Contains("lacks something"));
    CHECK_THAT(gpu::gpuFailureMessage("x", VK_TIMEOUT), Catch::Contains("unexpected") && Catch::Contains("VK_TIMEOUT"));
    // Every kind of advice names a remedy.
    for (const VkResult r : { VK_ERROR_DEVICE_LOST, VK_ERROR_OUT_OF_DEVICE_MEMORY, VK_ERROR_OUT_OF_HOST_MEMORY,
             VK_ERROR_INITIALIZATION_FAILED, VK_ERROR_FEATURE_NOT_PRESENT, VK_ERROR_UNKNOWN }) {
        const std::string advice = gpu::vkResultAdvice(r);
        INFO(gpu::vkResultName(r) << ": " << advice);
        CHECK((advice.find("FACESKETCH_DEVICE") != std::string::npos || advice.find("fewer faces") != std::string::npos));
    }
}

TEST_CASE("gpu error: VK_CHECK throws a GpuError, which is an Error, naming the call and line, and aborts nothing")
{
    REQUIRE_NOTHROW([] { VK_CHECK(VK_SUCCESS); }());
    bool caught = false;
    try {
        VK_CHECK(VK_ERROR_DEVICE_LOST);
    } catch (const gpu::GpuError& e) {
        caught = true;
        REQUIRE(e.result() == VK_ERROR_DEVICE_LOST);
        const std::string what = e.what();
        CHECK_THAT(what, Catch::StartsWith("VK_ERROR_DEVICE_LOST (") && Catch::Contains("error.cpp:"));
        CHECK_THAT(what, Catch::Contains("failed with VK_ERROR_DEVICE_LOST: ") && Catch::Contains("FACESKETCH_DEVICE"));
    }
    REQUIRE(caught);
    // Callers that catch facesketch::Error (every command) report GPU failures too.
    REQUIRE_THROWS_AS(gpu::gpuFail("waiting", VK_ERROR_DEVICE_LOST), Error);
    REQUIRE_THROWS_WITH(gpu::gpuFail("waiting", VK_ERROR_OUT_OF_DEVICE_MEMORY), Catch::StartsWith("waiting failed with"));
}

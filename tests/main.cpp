// Catch2 main for every FaceSketch test executable. A listener fails any test case during which
// the Vulkan validation layer reported a message, so no test can pass with validation noise.
// Debug builds trap floating-point exceptions (invalid, divide-by-zero, overflow), as libigl does.

#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "gpu/device.h"
#include "test_common.h"

#include <cfenv>
#include <cstdio>

namespace {

bool validationFailures = false;

struct ValidationListener : Catch::TestEventListenerBase {
    using TestEventListenerBase::TestEventListenerBase;

    void testCaseStarting(const Catch::TestCaseInfo&) override
    {
        facesketch::test::validationBaseline() = facesketch::gpu::validationMessageCount();
    }

    void testCaseEnded(const Catch::TestCaseStats& stats) override
    {
        const std::uint64_t messages = facesketch::gpu::validationMessageCount() - facesketch::test::validationBaseline();
        if (messages > 0) {
            std::fprintf(stderr, "FAILED: %llu Vulkan validation message(s) during test case '%s'\n",
                static_cast<unsigned long long>(messages), stats.testInfo.name.c_str());
            validationFailures = true;
        }
    }
};

} // namespace

CATCH_REGISTER_LISTENER(ValidationListener)

int main(int argc, char** argv)
{
#if !defined(NDEBUG) && defined(FE_INVALID)
    feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
#endif
    const int result = Catch::Session().run(argc, argv);
    const std::uint64_t beforeTeardown = facesketch::gpu::validationMessageCount();
    facesketch::test::releaseDevice();
    if (facesketch::gpu::validationMessageCount() != beforeTeardown) {
        std::fprintf(stderr, "FAILED: Vulkan validation message(s) while destroying the device (objects left alive?)\n");
        validationFailures = true;
    }
    return result != 0 ? result : (validationFailures ? 1 : 0);
}

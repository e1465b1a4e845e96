#pragma once
// Shared test helpers. GPU tests use one Vulkan device per process (ctest runs each test case in
// its own process) with validation forced on; any validation message fails the test case.

#include "gpu/device.h"

#include <catch2/catch.hpp>
#include <filesystem>

namespace facesketch::test {

/// The process-wide device, created on first use with validation required.
gpu::Device& device();
/// Destroys that device (if created), so that what the validation layer reports at teardown,
/// such as objects never destroyed, is counted before the process ends (tests/main.cpp).
void releaseDevice();

/// A fresh empty folder under the system temp dir, removed when the object dies.
class TempDir {
public:
    TempDir();
    ~TempDir();
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

/// Validation messages counted before the current test case started; a test that provokes
/// messages on purpose sets it to gpu::validationMessageCount() once it has checked them.
std::uint64_t& validationBaseline();

/// Writes `text` to `path` as bytes (for malformed-input tests).
void writeText(const std::filesystem::path& path, const std::string& text);

/// The bytes of the file at `path` (empty if it cannot be read).
std::string readBytes(const std::filesystem::path& path);

} // namespace facesketch::test

/// Fails the test if the validation layer reported anything since the test case started.
#define REQUIRE_NO_VALIDATION_MESSAGES() REQUIRE(::facesketch::gpu::validationMessageCount() == ::facesketch::test::validationBaseline())

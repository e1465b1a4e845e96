#include "test_common.h"

#include <cfenv>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>

namespace facesketch::test {

namespace {
std::optional<gpu::ScopedDevice>& holder()
{
    static std::optional<gpu::ScopedDevice> device;
    return device;
}
} // namespace

void releaseDevice()
{
    holder().reset();
}

std::uint64_t& validationBaseline()
{
    static std::uint64_t baseline = 0;
    return baseline;
}

gpu::Device& device()
{
    // Mesa's drivers compute with floating-point exceptions masked (lavapipe divides by zero in
    // its rasteriser set-up), so the traps that the test main arms for our CPU code are lifted
    // for the rest of a process that uses the GPU. ctest runs each test case in its own process.
    fedisableexcept(FE_ALL_EXCEPT);
    if (!holder())
        holder().emplace(gpu::DeviceOptions { .validation = true, .requireValidation = true });
    return **holder();
}

TempDir::TempDir()
{
    std::random_device seed;
    path_ = std::filesystem::temp_directory_path() / ("facesketch-test-" + std::to_string(seed()) + std::to_string(seed()));
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir()
{
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

void writeText(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

std::string readBytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

} // namespace facesketch::test

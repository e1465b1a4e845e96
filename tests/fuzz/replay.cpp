// Replays every file of tests/fuzz/<target>/ (the seed corpus and the input of every crash the
// fuzzers found, kept as regress-*) through the fuzz targets' entry points, in the normal and
// the sanitizer build: each must be read or refused with facesketch::Error, and the sanitizer
// build also fails on any memory error, leak or undefined behaviour they provoke again.
#include "entry_points.h"

#include "test_common.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace fs = std::filesystem;

namespace {

void replay(const std::string& name)
{
    const char* source = std::getenv("FACESKETCH_SOURCE_DIR");
    REQUIRE(source != nullptr);
    const fs::path folder = fs::path(source) / "tests" / "fuzz" / name;
    const facesketch::fuzz::Target& target = facesketch::fuzz::target(name);
    int seeds = 0;
    for (const auto& entry : fs::directory_iterator(folder)) {
        std::ifstream in(entry.path(), std::ios::binary);
        const std::string bytes { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
        INFO(entry.path().string());
        bool read = false;
        REQUIRE_NOTHROW(read = target.run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
        // Seeds are valid files (tests/fuzz/make_seeds.cpp): the reader must accept them.
        if (entry.path().filename().string().rfind("seed-", 0) == 0) {
            REQUIRE(read);
            ++seeds;
        }
    }
    REQUIRE(seeds > 0);
}

} // namespace

#define FACESKETCH_REPLAY(target)                                                                                                          \
    TEST_CASE("fuzz replay: every kept input of " target " is read or refused with an Error")                                              \
    {                                                                                                                                      \
        replay(target);                                                                                                                    \
    }

FACESKETCH_REPLAY("obj")
FACESKETCH_REPLAY("obj_vertices")
FACESKETCH_REPLAY("ply")
FACESKETCH_REPLAY("manifest")
FACESKETCH_REPLAY("ict_json")
FACESKETCH_REPLAY("model")
FACESKETCH_REPLAY("curvature_cache")
FACESKETCH_REPLAY("png")
FACESKETCH_REPLAY("session")

// Replays every file of tests/fuzz/<target>/ (the seed corpus and the input of every crash the
// fuzzers found, kept as regress-*) through the fuzz targets' entry points, in the normal and
// the sanitizer build: each must be read or refused with facesketch::Error, and the sanitizer
// build also fails on any memory error, leak or undefined behaviour they provoke again.
#include "entry_points.h"

#include "test_common.h"

#include <cfenv>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace fs = std::filesystem;

namespace {

void replay(const std::string& name)
{
    // Tests run in the source folder (cmake/facesketch.cmake).
    const char* source = std::getenv("FACESKETCH_SOURCE_DIR");
    const fs::path folder = fs::path(source && *source ? source : ".") / "tests" / "fuzz" / name;
    REQUIRE(fs::is_directory(folder));
    const facesketch::fuzz::Target& target = facesketch::fuzz::target(name);
    int seeds = 0;
    // As under libFuzzer, no floating-point traps (the debug test main sets them): a hostile
    // number such as 1e999 overflows inside the JSON parser's strtod before it is refused.
    const int traps = fegetexcept();
    fedisableexcept(FE_ALL_EXCEPT);
    struct Restore {
        int traps;
        ~Restore()
        {
            feclearexcept(FE_ALL_EXCEPT);
            if (traps)
                feenableexcept(traps);
        }
    } restore { traps };
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
FACESKETCH_REPLAY("pose_model")
FACESKETCH_REPLAY("feature_points")

// Tests of core/limits: file sizes checked before reading, and JSON nesting and string lengths
// refused by a scan before any parser builds the document.
#include "core/limits.h"

#include "core/error.h"
#include "test_common.h"

#include <filesystem>
#include <fstream>

using namespace facesketch;
using namespace facesketch::limits;

TEST_CASE("limits: a file larger than its limit is refused before it is read")
{
    test::TempDir dir;
    test::writeText(dir / "small.json", "{}");
    REQUIRE(readFileLimited(dir / "small.json", 2, "a test file") == "{}");
    REQUIRE_THROWS_WITH(readFileLimited(dir / "small.json", 1, "a test file"),
        Catch::Contains("small.json: 2 bytes, more than the 1 bytes a test file may have"));
    // A sparse 64 GiB file: refused from its size alone, in no time and no memory.
    {
        std::ofstream(dir / "huge.json");
    }
    std::filesystem::resize_file(dir / "huge.json", std::uint64_t(1) << 36);
    REQUIRE_THROWS_WITH(readFileLimited(dir / "huge.json", kMaxJsonFileBytes, "a manifest"), Catch::Contains("68719476736 bytes"));
    REQUIRE_THROWS_WITH(readFileLimited(dir / "none.json", 10, "a test file"), Catch::Contains("none.json: cannot open"));
    REQUIRE_THROWS_WITH(readFileLimited(dir.path(), 10, "a test file"), Catch::Contains("cannot open"));
}

TEST_CASE("limits: JSON nested deeper than the limit or with an over-long string is refused with its byte offset")
{
    const std::string atLimit = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
    REQUIRE_NOTHROW(checkJsonLimits(atLimit, "a.json"));
    const std::string deep = std::string(1000000, '[') + std::string(1000000, ']');
    REQUIRE_THROWS_WITH(checkJsonLimits(deep, "a.json"), Catch::Contains("a.json: byte 64: arrays and objects nested more than 64 deep"));
    // Brackets inside strings, also after an escaped quote, do not count.
    const std::string quoted = "{\"a\": \"\\\"" + std::string(1000, '[') + "\"}";
    REQUIRE_NOTHROW(checkJsonLimits(quoted, "a.json"));

    const std::string longest = "[\"" + std::string(kMaxJsonStringBytes - 1, 'x') + "\"]";
    REQUIRE_NOTHROW(checkJsonLimits(longest, "a.json"));
    const std::string tenMegabytes = "{\"name\": \"" + std::string(10 << 20, 'x') + "\"}";
    REQUIRE_THROWS_WITH(checkJsonLimits(tenMegabytes, "a.json"), Catch::Contains("a.json: byte 9: a string longer than 65536 bytes"));
    // An unterminated string is left to the parser's message, unless it is too long already.
    REQUIRE_NOTHROW(checkJsonLimits("[\"abc", "a.json"));
}

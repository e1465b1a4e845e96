#include "core/atomic_file.h"
#include "core/error.h"
#include "test_common.h"

#include <fstream>

using namespace facesketch;

TEST_CASE("writeFileAtomically: writes the whole file and leaves no temporary")
{
    test::TempDir dir;
    writeFileAtomically(dir / "a.txt", [](std::ostream& out) { out << "hello"; });
    REQUIRE(test::readBytes(dir / "a.txt") == "hello");
    int entries = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
        (void)e;
        ++entries;
    }
    REQUIRE(entries == 1);
}

TEST_CASE("writeFileAtomically: a failing writer keeps the previous file intact")
{
    test::TempDir dir;
    writeFileAtomically(dir / "a.txt", [](std::ostream& out) { out << "version 1"; });
    REQUIRE_THROWS_AS(writeFileAtomically(dir / "a.txt",
                          [](std::ostream& out) {
                              out << "half of version 2";
                              fail("disk on fire");
                          }),
        Error);
    REQUIRE(test::readBytes(dir / "a.txt") == "version 1");
    int entries = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
        (void)e;
        ++entries;
    }
    REQUIRE(entries == 1);
}

TEST_CASE("writeFileAtomically: a missing folder is an error naming the file")
{
    test::TempDir dir;
    REQUIRE_THROWS_WITH(writeFileAtomically(dir / "no/such/a.txt", [](std::ostream&) {}), Catch::Contains("a.txt"));
}

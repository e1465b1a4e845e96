#include "io/png.h"
#include "core/error.h"
#include "test_common.h"

using namespace facesketch;

TEST_CASE("png: round trip keeps every pixel")
{
    test::TempDir dir;
    Image image { 5, 3, {} };
    for (int i = 0; i < 5 * 3 * 4; ++i)
        image.pixels.push_back(static_cast<std::uint8_t>(i * 7));
    writePng(dir / "x.png", image);
    const Image back = readPng(dir / "x.png");
    REQUIRE(back.width == 5);
    REQUIRE(back.height == 3);
    REQUIRE(back.pixels == image.pixels);
}

TEST_CASE("png: unreadable and inconsistent images are errors naming the file")
{
    test::TempDir dir;
    test::writeText(dir / "bad.png", "not a png");
    REQUIRE_THROWS_WITH(readPng(dir / "bad.png"), Catch::Contains("bad.png"));
    Image wrong { 4, 4, std::vector<std::uint8_t>(10) };
    REQUIRE_THROWS_WITH(writePng(dir / "w.png", wrong), Catch::Contains("w.png"));
    REQUIRE_FALSE(std::filesystem::exists(dir / "w.png"));
}

#include "io/png.h"
#include "core/error.h"
#include "test_common.h"

#include <fstream>
#include <iterator>

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

TEST_CASE("png: a header declaring more pixels than the limit is refused before decoding")
{
    test::TempDir dir;
    Image small { 2, 2, std::vector<std::uint8_t>(16, 200) };
    writePng(dir / "small.png", small);
    std::ifstream in(dir / "small.png", std::ios::binary);
    std::string bytes { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
    // IHDR width and height (big-endian, bytes 16 and 20): 10,000 by 10,000, 400 MB as RGBA
    // (stb_image itself stops at 1 GB).
    const unsigned char side[4] = { 0x00, 0x00, 0x27, 0x10 };
    bytes.replace(16, 4, reinterpret_cast<const char*>(side), 4);
    bytes.replace(20, 4, reinterpret_cast<const char*>(side), 4);
    test::writeText(dir / "huge.png", bytes);
    REQUIRE_THROWS_WITH(readPng(dir / "huge.png"), Catch::Contains("huge.png: PNG of 10000 by 10000 pixels, more than the 67108864"));
}

TEST_CASE("png: a chunk claiming more bytes than the file holds is refused before stb allocates for it")
{
    // Found by the png fuzz target (tests/fuzz/png/regress-chunk-claiming-2-gb.png): stb_image
    // allocated the 2 GB an IDAT chunk claimed in a 100-byte file.
    test::TempDir dir;
    Image small { 2, 2, std::vector<std::uint8_t>(16, 100) };
    writePng(dir / "small.png", small);
    std::ifstream in(dir / "small.png", std::ios::binary);
    std::string bytes { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
    const size_t idat = bytes.find("IDAT") - 4;
    const unsigned char huge[4] = { 0x74, 0x00, 0x00, 0x00 };
    bytes.replace(idat, 4, reinterpret_cast<const char*>(huge), 4);
    test::writeText(dir / "claims.png", bytes);
    REQUIRE_THROWS_WITH(readPng(dir / "claims.png"),
        Catch::Contains(cat("claims.png: PNG chunk at byte ", idat, " claims 1946157056 bytes, more than the file holds")));
    REQUIRE(readPng(dir / "small.png").pixels == small.pixels);
}

// Tests of contours/curvature_cache_file: a file reads back exactly for its own batch, and every
// other file is refused with the reason, a huge one without being read.
#include "contours/curvature_cache_file.h"

#include "test_common.h"

#include <catch2/catch.hpp>
#include <fstream>

using namespace facesketch;

namespace {

GpuCurvature::PackedShapes shapesOf(std::uint32_t n)
{
    GpuCurvature::PackedShapes p;
    for (std::uint32_t i = 0; i < 4 * n; ++i)
        p.shapes.push_back(i * 2654435761u);
    for (std::uint32_t i = 0; i < n; ++i)
        p.c23.push_back(i * 40503u + 7);
    return p;
}

void writeBytes(const std::filesystem::path& path, const std::string& bytes)
{
    std::ofstream(path, std::ios::binary) << bytes;
}

} // namespace

TEST_CASE("curvature_cache_file: a file reads back for its batch only, and what is wrong is said")
{
    test::TempDir dir;
    const GpuCurvature::PackedShapes p = shapesOf(6);
    const std::string bytes = encodeCurvatureCache(42, 2, 3, p);
    REQUIRE(bytes.size() == 36 + 20 * 6 + 8);
    writeBytes(dir / "a.curv", bytes);
    GpuCurvature::PackedShapes back;
    std::string why;
    REQUIRE(readCurvatureCacheFile(dir / "a.curv", 42, 2, 3, back, why));
    REQUIRE(back.shapes == p.shapes);
    REQUIRE(back.c23 == p.c23);

    const auto refused = [&](const std::string& file, std::uint64_t key, std::uint64_t meshes, std::uint64_t vertices) {
        std::string reason;
        GpuCurvature::PackedShapes none;
        REQUIRE_FALSE(readCurvatureCacheFile(dir / file, key, meshes, vertices, none, reason));
        REQUIRE(none.shapes.empty());
        return reason;
    };
    REQUIRE(refused("a.curv", 43, 2, 3) == "made for other data");
    REQUIRE(refused("a.curv", 42, 3, 2) == "made for other data");
    writeBytes(dir / "short.curv", bytes.substr(0, bytes.size() - 1));
    REQUIRE(refused("short.curv", 42, 2, 3) == "truncated (163 bytes, expected 164)");
    std::string flipped = bytes;
    flipped[50] ^= 1;
    writeBytes(dir / "flipped.curv", flipped);
    REQUIRE(refused("flipped.curv", 42, 2, 3) == "checksum mismatch (corrupt)");
    writeBytes(dir / "tiny.curv", "FSK");
    REQUIRE(refused("tiny.curv", 42, 2, 3) == "not a curvature cache file");
    std::string version = bytes;
    version[8] = 9;
    writeBytes(dir / "version.curv", version);
    REQUIRE(refused("version.curv", 42, 2, 3) == "version 9, expected 1");
    REQUIRE(refused("missing.curv", 42, 2, 3).rfind("cannot be read", 0) == 0);

    // A sparse 64 GiB file with a valid header: refused from its size, without reading it.
    writeBytes(dir / "huge.curv", bytes.substr(0, 36));
    std::filesystem::resize_file(dir / "huge.curv", std::uint64_t(1) << 36);
    REQUIRE(refused("huge.curv", 42, 2, 3) == "truncated (68719476736 bytes, expected 164)");
}

TEST_CASE("curvature_cache_file: a batch of no vertices reads back empty")
{
    // Found by the curvature_cache fuzz target (tests/fuzz/curvature_cache/regress-batch-of-no-vertices.bin):
    // the empty shapes were copied through a null pointer.
    test::TempDir dir;
    writeBytes(dir / "empty.curv", encodeCurvatureCache(7, 3, 0, {}));
    GpuCurvature::PackedShapes back;
    std::string why;
    REQUIRE(readCurvatureCacheFile(dir / "empty.curv", 7, 3, 0, back, why));
    REQUIRE(back.shapes.empty());
    REQUIRE(back.c23.empty());
}

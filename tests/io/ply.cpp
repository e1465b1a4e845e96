// Tests of io/ply: ASCII and binary round trips, a big-endian file with extra properties and
// elements, and an error naming the file and line (ASCII) or element (binary) for each kind
// of malformed file.
#include "core/error.h"
#include "geometry/primitives.h"
#include "io/mesh_io.h"
#include "test_common.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>

using namespace facesketch;

namespace {

// Appends `value` to `out` most significant byte first.
template <typename T> void appendBigEndian(std::string& out, T value)
{
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::little)
        std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

Mesh asymmetricSphere()
{
    Mesh sphere = makeIcosphere(87.5, 2);
    sphere.V.col(0) *= 1.3;
    return sphere;
}

} // namespace

TEST_CASE("ply: binary and ASCII files read back to float precision")
{
    test::TempDir dir;
    const Mesh sphere = asymmetricSphere();
    for (const PlyEncoding encoding : { PlyEncoding::Binary, PlyEncoding::Ascii }) {
        writePly(dir / "s.ply", sphere, encoding);
        const Mesh back = readPly(dir / "s.ply");
        REQUIRE(back.V.rows() == sphere.V.rows());
        REQUIRE(back.F == sphere.F);
        // float32 storage: 114 mm * 2^-24 is under 1e-5.
        CHECK((back.V - sphere.V).cwiseAbs().maxCoeff() <= 1e-5);
        // Binary keeps the float itself; ASCII its 9 digits.
        if (encoding == PlyEncoding::Binary)
            CHECK(back.V == sphere.V.cast<float>().cast<double>());
    }
    writePly(dir / "b.ply", sphere);
    const std::string binary = test::readBytes(dir / "b.ply");
    CHECK(binary.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0);
    // Header, then 12 bytes per vertex and 13 per triangle.
    CHECK(binary.size() == binary.find("end_header\n") + 11 + 12 * 162 + 13 * 320);
}

TEST_CASE("ply: big-endian doubles, extra properties and elements, polygons and vertex_index")
{
    std::string file = "ply\nformat binary_big_endian 1.0\ncomment made by hand\nobj_info none\n"
                       "element vertex 4\nproperty uchar red\nproperty double x\nproperty double y\nproperty double z\n"
                       "element material 1\nproperty float shine\n"
                       "element face 2\nproperty list uchar int vertex_index\nproperty list ushort short other\nend_header\n";
    const double xyz[4][3] = { { 0, 0, 0 }, { 1.5, 0, 0 }, { 1.5, 2.25, 0 }, { 0, 2.25, -1 } };
    for (const auto& p : xyz) {
        appendBigEndian<std::uint8_t>(file, 200);
        for (double c : p)
            appendBigEndian(file, c);
    }
    appendBigEndian(file, 0.5f);
    // A quad, then a triangle; each with a list the reader must skip.
    appendBigEndian<std::uint8_t>(file, 4);
    for (std::int32_t i : { 0, 1, 2, 3 })
        appendBigEndian(file, i);
    appendBigEndian<std::uint16_t>(file, 1);
    appendBigEndian<std::int16_t>(file, -7);
    appendBigEndian<std::uint8_t>(file, 3);
    for (std::int32_t i : { 3, 1, 0 })
        appendBigEndian(file, i);
    appendBigEndian<std::uint16_t>(file, 0);

    test::TempDir dir;
    test::writeText(dir / "be.ply", file);
    const Mesh m = readPly(dir / "be.ply");
    REQUIRE(m.V.rows() == 4);
    for (int v = 0; v < 4; ++v)
        CHECK(m.V.row(v) == Eigen::RowVector3d(xyz[v][0], xyz[v][1], xyz[v][2]));
    REQUIRE(m.F.rows() == 3);
    CHECK(m.F.row(0) == Eigen::RowVector3i(0, 1, 2));
    CHECK(m.F.row(1) == Eigen::RowVector3i(0, 2, 3));
    CHECK(m.F.row(2) == Eigen::RowVector3i(3, 1, 0));
}

TEST_CASE("ply: malformed ASCII files name the file and line")
{
    test::TempDir dir;
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const auto bad = [&](const std::string& text, const std::string& expected) {
        test::writeText(dir / "bad.ply", text);
        REQUIRE_THROWS_WITH(readPly(dir / "bad.ply"), Catch::Contains("bad.ply" + expected));
    };
    bad(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ":13: face 0 has vertex index 3 outside [0, 3)");
    bad(header + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", ":11: vertex 1 has non-finite y");
    bad(header + "0 0 0\n1 0 0\n", ":12: file ends at vertex 2 of 3");              // truncated
    bad(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", ":13: face 0 has too few values"); // wrong count
    bad(header + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", ":11: vertex 1 has too few values");
    bad(header + "0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n", ":10: vertex 0 has more values");
    bad(header + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", ":13: face 0 has 2 vertices, at least 3 needed");
    bad(header + "0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n", ":12: vertex 2: y 'one' is not a number");
    bad(header + "0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n", ":13: face 0: list length -1 is invalid");
    bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n", ": 'vertex' element lacks scalar x, y and z");
    bad("ply\nformat ascii 1.0\nelement vertex 1\n", ":3: header ends without 'end_header'");
    bad("ply\nformat ebcdic 1.0\n", ":2: unknown format 'ebcdic'");
    bad("ply\nformat ascii 1.0\nproperty float x\n", ":3: property before any element");
    bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n", ":4: bad property 'property quad x'");
    bad("ply\nelement vertex 0\nend_header\n", ": header has no 'format' line");
    bad("plx\n", ":1: not a PLY file");
    REQUIRE_THROWS_WITH(readPly(dir / "missing.ply"), Catch::Contains("missing.ply: cannot open"));
}

TEST_CASE("ply: malformed binary files name the file and element")
{
    test::TempDir dir;
    writePly(dir / "ok.ply", makeIcosphere(1, 1), PlyEncoding::Binary);
    const std::string bytes = test::readBytes(dir / "ok.ply");
    // Cut short: the error names the element being read.
    test::writeText(dir / "cut.ply", bytes.substr(0, bytes.size() - 20));
    REQUIRE_THROWS_WITH(readPly(dir / "cut.ply"), Catch::Contains("cut.ply: file ends inside face 78") && Catch::Contains("truncated"));
    // An index out of range.
    std::string corrupt = bytes;
    const std::int32_t big = 1000;
    std::memcpy(&corrupt[bytes.size() - 4], &big, 4);
    test::writeText(dir / "corrupt.ply", corrupt);
    REQUIRE_THROWS_WITH(readPly(dir / "corrupt.ply"), Catch::Contains("corrupt.ply: face 79 has vertex index 1000"));
    // A non-finite coordinate.
    std::string nan = bytes;
    const float notANumber = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&nan[bytes.find("end_header\n") + 11 + 12 * 5 + 4], &notANumber, 4);
    test::writeText(dir / "nan.ply", nan);
    REQUIRE_THROWS_WITH(readPly(dir / "nan.ply"), Catch::Contains("nan.ply: vertex 5 has non-finite y"));
}

TEST_CASE("ply: hostile headers are refused before anything of their size is allocated")
{
    test::TempDir dir;
    const auto refused = [&](const std::string& bytes, const std::string& expected) {
        test::writeText(dir / "hostile.ply", bytes);
        REQUIRE_THROWS_WITH(readPly(dir / "hostile.ply"), Catch::Contains("hostile.ply") && Catch::Contains(expected));
    };
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    // 4 billion vertices (48 GB as doubles) announced by a 100-byte file.
    refused("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" + xyz + "end_header\n",
        ":3: element 'vertex' declares 4000000000 instances, more than the 268435456");
    // A count whose product with the instance size would overflow 64 bits.
    refused("ply\nformat binary_little_endian 1.0\nelement vertex 4611686018427387904\n" + xyz + "end_header\n", "more than the 268435456");
    // Within the element limit but above the vertex limit.
    refused("ply\nformat ascii 1.0\nelement vertex 100000000\n" + xyz + "end_header\n",
        "declares 100000000 vertices, more than the 67108864 a mesh may have");
    // Within every limit, but more than the bytes that follow can hold.
    refused("ply\nformat binary_little_endian 1.0\nelement vertex 60000000\n" + xyz + "end_header\n" + std::string(12, '\0'),
        "need at least 720000000 bytes, but only 12 follow it");
    refused("ply\nformat ascii 1.0\nelement vertex 3\n" + xyz
            + "element face 50000000\nproperty list uchar int vertex_indices\nend_header\n"
              "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        "need at least 50000003 bytes, but only 26 follow it");
    // A polygon longer than the limit, and a face index past the vertex count as a huge float
    // (converting it to an integer unchecked would be undefined behaviour).
    refused("ply\nformat ascii 1.0\nelement vertex 3\n" + xyz
            + "element face 1\nproperty list int int vertex_indices\nend_header\n"
              "0 0 0\n1 0 0\n0 1 0\n70000 0 1 2\n",
        "face 0: list length 70000 is invalid (at most 65536)");
    std::string floatIndex = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + xyz
        + "element face 1\nproperty list uchar float vertex_indices\nend_header\n";
    const float corners[12] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 1e30f };
    floatIndex.append(reinterpret_cast<const char*>(corners), 36);
    floatIndex += '\3';
    floatIndex.append(reinterpret_cast<const char*>(corners + 9), 12);
    refused(floatIndex, "face 0 has vertex index 1.00000002e+30 outside [0, 3)");
    // Billions of instances of an element without properties cost no time.
    test::writeText(dir / "empty-elements.ply",
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + xyz + "element nothing 268435456\nend_header\n"
            + std::string(reinterpret_cast<const char*>(corners), 36));
    REQUIRE(readPly(dir / "empty-elements.ply").vertexCount() == 3);
}

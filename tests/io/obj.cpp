// Tests of io/obj: a round trip, the statement forms a reader meets in the wild, and a
// "FILE:LINE: what" error for each kind of bad statement.
#include "core/error.h"
#include "geometry/primitives.h"
#include "io/mesh_io.h"
#include "test_common.h"

#include <fstream>
#include <iterator>

using namespace facesketch;

namespace {

std::string readText(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

} // namespace

TEST_CASE("obj: a written mesh reads back to float precision")
{
    test::TempDir dir;
    Mesh sphere = makeIcosphere(87.5, 2);
    sphere.V.col(0) *= 1.3; // not a symmetric shape
    writeObj(dir / "s.obj", sphere);
    const Mesh back = readObj(dir / "s.obj");
    REQUIRE(back.V.rows() == sphere.V.rows());
    REQUIRE(back.F == sphere.F);
    // Written with 9 significant digits, read through tinyobjloader's float32: 114 mm * 2^-24.
    CHECK((back.V - sphere.V).cwiseAbs().maxCoeff() <= 114.0 * 0x1p-24);
    const std::string text = readText(dir / "s.obj");
    CHECK(text.rfind("# FaceSketch mesh: 162 vertices, 320 triangles\nv ", 0) == 0);
}

TEST_CASE("obj: polygons, negative indices, texture/normal forms, w and CRLF")
{
    test::TempDir dir;
    test::writeText(dir / "q.obj",
        "# quad\r\nv 0 0 0 1\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nvt 0 0\r\nvn 0 0 1\r\n"
        "f 1/1/1 2/1/1 3/1/1 4/1/1\r\nf -4//1 -2//1 -1//1\r\nf 1/1 2/1 4/1\r\n");
    const Mesh m = readObj(dir / "q.obj");
    REQUIRE(m.V.rows() == 4);
    CHECK(m.V.row(2) == Eigen::RowVector3d(1, 1, 0));
    REQUIRE(m.F.rows() == 4);
    // The quad is fanned from its first vertex, one face per `f` line in order.
    CHECK(m.F.row(0) == Eigen::RowVector3i(0, 1, 2));
    CHECK(m.F.row(1) == Eigen::RowVector3i(0, 2, 3));
    CHECK(m.F.row(2) == Eigen::RowVector3i(0, 2, 3));
    CHECK(m.F.row(3) == Eigen::RowVector3i(0, 1, 3));
}

TEST_CASE("obj: malformed files name the file and line")
{
    test::TempDir dir;
    const auto bad = [&](const std::string& text, const std::string& expected) {
        test::writeText(dir / "bad.obj", text);
        REQUIRE_THROWS_WITH(readObj(dir / "bad.obj"), Catch::Contains("bad.obj:" + expected));
    };
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "4: face index 4 refers to no vertex");
    bad("v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n", "3: vertex coordinate y is nan");
    bad("v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n", "3: vertex has 2 coordinates");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "4: face has 2 vertices"); // truncated face
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "4: face vertex 'x' is not an index");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "4: face index 0 refers to no vertex");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1\n", "4: face repeats vertex 1");
    bad("v 0 0 0\nv 1 zero 0\n", "2: vertex coordinate 'zero' is not a number");
    // A face may only refer to vertices defined above it.
    bad("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", "3: face index 3 refers to no vertex (2 defined so far)");
    REQUIRE_THROWS_WITH(readObj(dir / "missing.obj"), Catch::Contains("missing.obj: cannot open"));
}

TEST_CASE("obj: writing an invalid mesh fails before touching the file")
{
    test::TempDir dir;
    Mesh mesh = makeIcosphere(1, 0);
    writeObj(dir / "m.obj", mesh);
    const std::string before = readText(dir / "m.obj");
    mesh.F(3, 1) = static_cast<int>(mesh.V.rows());
    REQUIRE_THROWS_WITH(writeObj(dir / "m.obj", mesh), Catch::Contains("m.obj: triangle 3 has vertex index 12"));
    CHECK(readText(dir / "m.obj") == before);
}

// Tests of io/obj: a round trip, the statement forms a reader meets in the wild, a
// "FILE:LINE: what" error for each kind of bad statement, and readObjVertices (double precision).
#include "core/error.h"
#include "geometry/primitives.h"
#include "io/mesh_io.h"
#include "test_common.h"

using namespace facesketch;

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
    const std::string text = test::readBytes(dir / "s.obj");
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
    const std::string before = test::readBytes(dir / "m.obj");
    mesh.F(3, 1) = static_cast<int>(mesh.V.rows());
    REQUIRE_THROWS_WITH(writeObj(dir / "m.obj", mesh), Catch::Contains("m.obj: triangle 3 has vertex index 12"));
    CHECK(test::readBytes(dir / "m.obj") == before);
}

TEST_CASE("obj: readObjVertices reads every v line in double precision and skips the rest")
{
    test::TempDir dir;
    test::writeText(dir / "a.obj",
        "# comment\n"
        "mtllib a.mtl\n"
        "v 0.1234567890123456 -2.5e-3 12\r\n"
        "vn 0 0 1\n"
        "vt 0.5 0.5\n"
        "v\t1e2\t -7.25   3.0000000001 1.0\n"
        "f 1 2 2\n"
        "v -0 1 2");
    const Vertices V = readObjVertices(dir / "a.obj");
    REQUIRE(V.rows() == 3);
    REQUIRE(V(0, 0) == 0.1234567890123456);
    REQUIRE(V(0, 1) == -2.5e-3);
    REQUIRE(V(0, 2) == 12);
    REQUIRE(V(1, 0) == 100);
    REQUIRE(V(1, 1) == -7.25);
    REQUIRE(V(1, 2) == 3.0000000001); // beyond float precision: readObj would round it
    REQUIRE(V.row(2) == Eigen::RowVector3d(0, 1, 2));
    // A file of `v` lines only (no faces) is accepted, and an empty one gives 0 rows.
    test::writeText(dir / "empty.obj", "# nothing\n");
    REQUIRE(readObjVertices(dir / "empty.obj").rows() == 0);
}

TEST_CASE("obj: readObjVertices names the file, line and coordinate of a bad v line")
{
    test::TempDir dir;
    test::writeText(dir / "short.obj", "v 1 2 3\nv 1 2\n");
    REQUIRE_THROWS_WITH(
        readObjVertices(dir / "short.obj"), Catch::Contains("short.obj:2: vertex coordinate z is missing or not a number: 'v 1 2'"));
    test::writeText(dir / "word.obj", "# x\n\nv 1 2x 3\n");
    REQUIRE_THROWS_WITH(readObjVertices(dir / "word.obj"), Catch::Contains("word.obj:3: vertex coordinate y is missing or not a number"));
    test::writeText(dir / "inf.obj", "v 1 2 3\nv nan 2 3\n");
    REQUIRE_THROWS_WITH(readObjVertices(dir / "inf.obj"), Catch::Contains("inf.obj:2: vertex coordinate x is nan"));
    REQUIRE_THROWS_WITH(readObjVertices(dir / "none.obj"), Catch::Contains("none.obj: cannot open"));
}

TEST_CASE("obj: a polygon of more than 255 corners is refused (tinyobjloader counts them in a byte)")
{
    test::TempDir dir;
    std::string text, face = "f";
    for (int i = 1; i <= 256; ++i) {
        text += cat("v ", i, " ", i % 7, " 0\n");
        face += cat(" ", i);
    }
    test::writeText(dir / "big.obj", text + face + "\n");
    REQUIRE_THROWS_WITH(readObj(dir / "big.obj"), Catch::Contains("big.obj:257: face has 256 vertices, at most 255 are supported"));
    // 255 corners read as a fan of 253 triangles.
    test::writeText(dir / "ok.obj", text + face.substr(0, face.rfind(' ')) + "\n");
    REQUIRE(readObj(dir / "ok.obj").triangleCount() == 253);
}

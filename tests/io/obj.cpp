// io/obj: readObjVertices, the double-precision reader of `v` lines (readObj and writeObj are
// exercised through readMesh in tests/io/mesh_io.cpp).
#include "core/error.h"
#include "io/mesh_io.h"
#include "test_common.h"

using namespace facesketch;

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

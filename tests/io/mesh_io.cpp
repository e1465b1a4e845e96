#include "io/mesh_io.h"
#include "core/error.h"
#include "geometry/primitives.h"
#include "test_common.h"

#include <cstring>
#include <fstream>

using namespace facesketch;

static void requireSameMesh(const Mesh& a, const Mesh& b, double tolerance)
{
    REQUIRE(a.V.rows() == b.V.rows());
    REQUIRE(a.F == b.F);
    REQUIRE((a.V - b.V).cwiseAbs().maxCoeff() <= tolerance);
}

TEST_CASE("mesh_io: OBJ, binary PLY and ASCII PLY round trips")
{
    test::TempDir dir;
    Mesh sphere = makeIcosphere(87.5, 2);
    sphere.V.col(0) *= 1.3; // not a symmetric shape
    writeObj(dir / "s.obj", sphere);
    requireSameMesh(readMesh(dir / "s.obj"), sphere, 1e-5);
    writePly(dir / "s.ply", sphere, PlyEncoding::Binary);
    requireSameMesh(readMesh(dir / "s.ply"), sphere, 1e-4); // float32 storage: 87.5 mm * 2^-24
    writePly(dir / "a.PLY", sphere, PlyEncoding::Ascii);
    requireSameMesh(readMesh(dir / "a.PLY"), sphere, 1e-4);
}

TEST_CASE("mesh_io: OBJ polygons, negative indices and texture/normal forms")
{
    test::TempDir dir;
    test::writeText(dir / "q.obj",
        "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
        "f 1/1/1 2/1/1 3/1/1 4/1/1\nf -4//1 -2//1 -1//1\n");
    const Mesh m = readMesh(dir / "q.obj");
    REQUIRE(m.V.rows() == 4);
    REQUIRE(m.F.rows() == 3);
    REQUIRE(m.F.row(0) == Eigen::RowVector3i(0, 1, 2));
    REQUIRE(m.F.row(1) == Eigen::RowVector3i(0, 2, 3));
    REQUIRE(m.F.row(2) == Eigen::RowVector3i(0, 2, 3));
}

TEST_CASE("mesh_io: malformed OBJ files name the file and line")
{
    test::TempDir dir;
    const auto bad = [&](const std::string& text, const std::string& expected) {
        test::writeText(dir / "bad.obj", text);
        REQUIRE_THROWS_WITH(readMesh(dir / "bad.obj"), Catch::Contains("bad.obj:" + expected));
    };
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "4: face index 4 refers to no vertex");
    bad("v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n", "3: vertex coordinate y is nan");
    bad("v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n", "3: vertex has 2 coordinates");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "4: face has 2 vertices"); // truncated face
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "4: face vertex 'x' is not an index");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "4: face index 0 refers to no vertex");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1\n", "4: face repeats vertex 1");
    REQUIRE_THROWS_WITH(readMesh(dir / "missing.obj"), Catch::Contains("missing.obj: cannot open"));
    REQUIRE_THROWS_WITH(readMesh(dir / "x.stl"), Catch::Contains("unknown mesh format"));
}

TEST_CASE("mesh_io: malformed PLY files name the file and line or element")
{
    test::TempDir dir;
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const auto bad = [&](const std::string& text, const std::string& expected) {
        test::writeText(dir / "bad.ply", text);
        REQUIRE_THROWS_WITH(readMesh(dir / "bad.ply"), Catch::Contains("bad.ply" + expected));
    };
    bad(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ":13: face 0 has vertex index 3 outside [0, 3)");
    bad(header + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", ":11: vertex 1 has non-finite y");
    bad(header + "0 0 0\n1 0 0\n", ":12: file ends at vertex 2 of 3");              // truncated
    bad(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", ":13: face 0 has too few values"); // wrong count
    bad(header + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", ":11: vertex 1 has too few values");
    bad(header + "0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n", ":10: vertex 0 has more values");
    bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n", ": 'vertex' element lacks scalar x, y and z");
    bad("ply\nformat ascii 1.0\nelement vertex 1\n", ":3: header ends without 'end_header'");
    bad("plx\n", ":1: not a PLY file");

    // Binary: cut a valid file short; the error names the element being read.
    writePly(dir / "ok.ply", makeIcosphere(1, 1), PlyEncoding::Binary);
    std::ifstream in(dir / "ok.ply", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    test::writeText(dir / "cut.ply", bytes.substr(0, bytes.size() - 20));
    REQUIRE_THROWS_WITH(readMesh(dir / "cut.ply"), Catch::Contains("cut.ply: file ends inside face 78") && Catch::Contains("truncated"));
    // Binary: an index out of range.
    std::string corrupt = bytes;
    const std::int32_t big = 1000;
    std::memcpy(&corrupt[bytes.size() - 4], &big, 4);
    test::writeText(dir / "corrupt.ply", corrupt);
    REQUIRE_THROWS_WITH(readMesh(dir / "corrupt.ply"), Catch::Contains("corrupt.ply: face 79 has vertex index 1000"));
}

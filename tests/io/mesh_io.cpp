// Tests of io/mesh_io: readMesh and writeMesh pick OBJ or PLY by extension, whatever its
// case, and name the file for any other. The formats themselves: tests/io/obj.cpp, ply.cpp.
#include "io/mesh_io.h"
#include "core/error.h"
#include "geometry/primitives.h"
#include "test_common.h"

#include <fstream>

using namespace facesketch;

namespace {

std::string firstLine(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string line;
    std::getline(in, line);
    return line;
}

} // namespace

TEST_CASE("mesh_io: the extension picks the format, in any case")
{
    test::TempDir dir;
    const Mesh sphere = makeIcosphere(87.5, 2);
    writeMesh(dir / "s.obj", sphere);
    CHECK(firstLine(dir / "s.obj").rfind("# FaceSketch mesh", 0) == 0);
    writeMesh(dir / "s.PLY", sphere);
    CHECK(firstLine(dir / "s.PLY") == "ply");
    for (const char* name : { "s.obj", "s.PLY" }) {
        const Mesh back = readMesh(dir / name);
        REQUIRE(back.F == sphere.F);
        CHECK((back.V - sphere.V).cwiseAbs().maxCoeff() <= 1e-5);
    }
    // writeMesh's PLY is binary; an ASCII one reads the same way.
    writePly(dir / "a.Ply", sphere, PlyEncoding::Ascii);
    CHECK(readMesh(dir / "a.Ply").F == sphere.F);
}

TEST_CASE("mesh_io: other extensions and missing files are named")
{
    test::TempDir dir;
    REQUIRE_THROWS_WITH(readMesh(dir / "x.stl"), Catch::Contains("x.stl: unknown mesh format '.stl'"));
    REQUIRE_THROWS_WITH(writeMesh(dir / "x.off", makeIcosphere(1, 0)), Catch::Contains("x.off: unknown mesh format '.off'"));
    CHECK(!std::filesystem::exists(dir / "x.off"));
    REQUIRE_THROWS_WITH(readMesh(dir / "missing.obj"), Catch::Contains("missing.obj: cannot open"));
    REQUIRE_THROWS_WITH(readMesh(dir / "missing.ply"), Catch::Contains("missing.ply: cannot open"));
}

#include "core/mesh.h"
#include "core/error.h"

#include <catch2/catch.hpp>
#include <limits>

using namespace facesketch;

static Mesh triangle()
{
    Mesh m;
    m.V.resize(3, 3);
    m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    m.F.resize(1, 3);
    m.F << 0, 1, 2;
    return m;
}

TEST_CASE("validateMesh: accepts a good triangle")
{
    REQUIRE_NOTHROW(validateMesh(triangle(), "t"));
}

TEST_CASE("validateMesh: names the non-finite vertex and coordinate")
{
    Mesh m = triangle();
    m.V(2, 1) = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(validateMesh(m, "face.ply"), Catch::Contains("face.ply: vertex 2") && Catch::Contains("coordinate y"));
}

TEST_CASE("validateMesh: names an index out of range and a repeated vertex")
{
    Mesh m = triangle();
    m.F(0, 2) = 3;
    REQUIRE_THROWS_WITH(validateMesh(m, "m"), Catch::Contains("triangle 0 has vertex index 3 outside [0, 3)"));
    m.F(0, 2) = 1;
    REQUIRE_THROWS_WITH(validateMesh(m, "m"), Catch::Contains("triangle 0 repeats a vertex"));
}

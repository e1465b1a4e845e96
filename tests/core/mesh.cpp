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

TEST_CASE("mesh views: asVector sees a face's rows end to end, without a copy")
{
    Vertices V(3, 3);
    V << 1, 2, 3, 4, 5, 6, 7, 8, 9;
    Eigen::Map<Eigen::VectorXd> x = asVector(V);
    REQUIRE(x.size() == 9);
    REQUIRE(x.data() == V.data());
    for (Eigen::Index v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c)
            REQUIRE(x[3 * v + c] == V(v, c));
    x[5] = -1; // vertex 1, z
    REQUIRE(V(1, 2) == -1);
    const Vertices& constV = V;
    REQUIRE(asVector(constV).sum() == 1 + 2 + 3 + 4 + 5 - 1 + 7 + 8 + 9);
}

TEST_CASE("mesh views: asVertices sees a 3#V vector as #V by 3, and refuses a partial vertex")
{
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(12, 0, 11);
    Eigen::Map<Vertices> V = asVertices(x);
    REQUIRE(V.rows() == 4);
    REQUIRE(V.data() == x.data());
    REQUIRE(V(2, 1) == 7);
    V.row(3) = Eigen::RowVector3d(-1, -2, -3);
    REQUIRE(x.tail(3) == Eigen::Vector3d(-1, -2, -3));
    const Eigen::VectorXd& constX = x;
    REQUIRE(asVertices(constX).row(0) == Eigen::RowVector3d(0, 1, 2));
    // A round trip through both views is the identity.
    Vertices copy = asVertices(x);
    REQUIRE(asVector(copy) == x);
    Eigen::VectorXd partial(8);
    REQUIRE_THROWS_WITH(asVertices(partial), Catch::Contains("8 coordinates is not a whole number of xyz vertices"));
}

TEST_CASE("mesh views: meshInBatch sees one mesh of a mesh-major float array and refuses one beyond it")
{
    std::vector<float> batch(2 * 4 * 3);
    for (size_t i = 0; i < batch.size(); ++i)
        batch[i] = float(i);
    Eigen::Map<VerticesF> second = meshInBatch(batch, 4, 1);
    REQUIRE(second.rows() == 4);
    REQUIRE(second(0, 0) == 12.0f);
    REQUIRE(second(3, 2) == 23.0f);
    second(1, 1) = -5.0f;
    REQUIRE(batch[12 + 3 + 1] == -5.0f);
    const std::vector<float>& constBatch = batch;
    REQUIRE(meshInBatch(constBatch, 4, 0)(2, 0) == 6.0f);
    REQUIRE_THROWS_WITH(meshInBatch(batch, 4, 2), Catch::Contains("no mesh 2 of 4 vertices in 24 floats"));
    REQUIRE_THROWS_WITH(meshInBatch(batch, 5, 1), Catch::Contains("no mesh 1 of 5 vertices"));
}

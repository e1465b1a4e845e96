// `import meshes`: a folder of meshes in correspondence becomes a dataset; bad input stops
// with the file (and line) named and leaves no output folder behind.
#include "dataset/import_meshes.h"
#include "core/error.h"
#include "dataset/dataset.h"
#include "io/mesh_io.h"
#include "test_common.h"

using namespace facesketch;
using namespace facesketch::dataset;
namespace fs = std::filesystem;

namespace {

// An n x n grid in the xy plane, bumped by `height` at the centre.
Mesh grid(int n, double height)
{
    Mesh m;
    m.V.resize(n * n, 3);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
            const double x = c - (n - 1) / 2.0, y = r - (n - 1) / 2.0;
            m.V.row(r * n + c) << x, y, height * std::exp(-(x * x + y * y) / 4);
        }
    m.F.resize(2 * (n - 1) * (n - 1), 3);
    int f = 0;
    for (int r = 0; r + 1 < n; ++r)
        for (int c = 0; c + 1 < n; ++c) {
            const int a = r * n + c;
            m.F.row(f++) << a, a + 1, a + n + 1;
            m.F.row(f++) << a, a + n + 1, a + n;
        }
    return m;
}

void writeFolder(const fs::path& dir, int count)
{
    fs::create_directories(dir);
    for (int i = 0; i < count; ++i) {
        const Mesh m = grid(9, 1 + 0.1 * i);
        if (i % 2)
            writePly(dir / cat("face", i, ".ply"), m);
        else
            writeObj(dir / cat("face", i, ".obj"), m);
    }
}

} // namespace

TEST_CASE("import_meshes: a folder of OBJ and PLY meshes becomes a dataset in mm with labels")
{
    test::TempDir dir;
    writeFolder(dir / "in", 6);
    test::writeText(dir / "in" / "landmarks.json",
        R"({"units": "cm", "landmarks": {"prn": 40}, "mpeg4": {"9.3": 40},
                        "contours": {"eyebrow_l": [36, 37, 38]}, "excluded": [0, 1]})");
    const Manifest m = importMeshes(dir / "in", dir / "out");
    const Dataset d = openDataset(dir / "out");
    REQUIRE(d.manifest.samples.size() == 6);
    REQUIRE(d.manifest.samples[0].name == "face0");
    REQUIRE(d.manifest.landmarks.at("prn") == 40);
    REQUIRE(d.manifest.contours.at("eyebrow_l") == std::vector<int> { 36, 37, 38 });
    REQUIRE(d.manifest.component("skin")->size() == 81);
    const Mesh face3 = loadMesh(d, d.manifest.samples[3].file);
    const Mesh original = grid(9, 1.3);
    REQUIRE((face3.V - 10 * original.V).cwiseAbs().maxCoeff() < 1e-4); // cm -> mm
    REQUIRE(m.samples.size() == 6);
}

TEST_CASE("import_meshes: roles follow a seeded shuffle of the 182/48/20 split")
{
    const auto roles = shuffledRoles(250, 7);
    REQUIRE(std::count(roles.begin(), roles.end(), Role::Train) == 182);
    REQUIRE(std::count(roles.begin(), roles.end(), Role::Contour) == 48);
    REQUIRE(std::count(roles.begin(), roles.end(), Role::Test) == 20);
    REQUIRE(shuffledRoles(250, 7) == roles);
    REQUIRE(shuffledRoles(250, 8) != roles);
    // Not simply train first: the shuffle mixes the roles over the file order.
    REQUIRE(std::count(roles.begin(), roles.begin() + 182, Role::Train) < 182);
}

TEST_CASE("import_meshes: --vertices simplifies and keeps the labelled vertices")
{
    test::TempDir dir;
    writeFolder(dir / "in", 3);
    test::writeText(dir / "in" / "landmarks.json", R"({"landmarks": {"prn": 40, "ex_l": 44}})");
    MeshImportOptions o;
    o.vertices = 30;
    const Manifest m = importMeshes(dir / "in", dir / "out", o);
    REQUIRE(m.vertexCount < 60);
    const Dataset d = openDataset(dir / "out");
    const Mesh face0 = loadMesh(d, d.manifest.samples[0].file);
    REQUIRE((face0.V.row(m.landmarks.at("prn")) - grid(9, 1).V.row(40)).norm() < 1e-5);
    REQUIRE((face0.V.row(m.landmarks.at("ex_l")) - grid(9, 1).V.row(44)).norm() < 1e-5);
}

TEST_CASE("import_meshes: bad input names the file and line and writes nothing")
{
    test::TempDir dir;
    auto fresh = [&] {
        fs::remove_all(dir / "in");
        writeFolder(dir / "in", 3);
    };
    auto refused = [&](const std::string& expected) {
        REQUIRE_THROWS_WITH(importMeshes(dir / "in", dir / "out"), Catch::Contains(expected));
        REQUIRE(!fs::exists(dir / "out"));
        for (const auto& e : fs::directory_iterator(dir.path()))
            REQUIRE(e.path().filename().string().find(".tmp") == std::string::npos);
    };

    fresh();
    writeObj(dir / "in" / "face9.obj", grid(8, 1));
    refused("face9.obj: has 64 vertices, face0.obj has 81");

    fresh();
    Mesh flipped = grid(9, 1);
    flipped.F.row(5) = flipped.F.row(5).reverse().eval();
    writeObj(dir / "in" / "face9.obj", flipped);
    refused("face9.obj: triangle 5");

    fresh();
    test::writeText(dir / "in" / "face9.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
    refused("face9.obj:3");

    fresh();
    test::writeText(dir / "in" / "face9.obj", "v 0 0 0\nv 1 0\n");
    refused("face9.obj:2");

    fresh();
    test::writeText(dir / "in" / "landmarks.json", R"({"landmarks": {"prn": 500}})");
    refused("landmarks.prn: vertex 500");

    fresh();
    test::writeText(dir / "in" / "landmarks.json", R"({"landmarks": {"prn": "tip"}})");
    refused("landmarks.json: landmarks.prn: '\"tip\"' is not a vertex index");

    fresh();
    test::writeText(dir / "in" / "landmarks.json", R"({"units": "inch"})");
    refused("landmarks.json: units 'inch' are not mm, cm or m");

    fresh();
    test::writeText(dir / "in" / "landmarks.json", R"({"units": 10})");
    refused("landmarks.json: units: 10 is not a string");

    REQUIRE_THROWS_WITH(importMeshes(dir / "missing", dir / "out"), Catch::Contains("missing: does not exist"));
    fs::create_directories(dir / "empty");
    REQUIRE_THROWS_WITH(importMeshes(dir / "empty", dir / "out"), Catch::Contains("no .obj or .ply meshes"));

    // A failing import leaves an existing dataset untouched.
    fresh();
    importMeshes(dir / "in", dir / "out");
    writeObj(dir / "in" / "face9.obj", grid(8, 1));
    REQUIRE_THROWS(importMeshes(dir / "in", dir / "out"));
    REQUIRE(openDataset(dir / "out").manifest.samples.size() == 3);
}

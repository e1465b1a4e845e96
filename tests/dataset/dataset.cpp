// Dataset folders: atomic writing, opening with file checks, loading shapes.
#include "dataset/dataset.h"
#include "core/error.h"
#include "io/mesh_io.h"
#include "test_common.h"

using namespace facesketch;
using namespace facesketch::dataset;
namespace fs = std::filesystem;

namespace {

Manifest square(int samples)
{
    Manifest m;
    m.vertexCount = 4;
    m.topology.resize(2, 3);
    m.topology << 0, 1, 2, 0, 2, 3;
    m.components = { { "skin", 0, 4 } };
    for (int i = 0; i < samples; ++i)
        m.samples.push_back({ cat("s", i), cat("s", i, ".ply"), i == 0 ? Role::Test : Role::Train });
    return m;
}

Mesh squareMesh(const Manifest& m, double scale)
{
    Mesh mesh;
    mesh.V.resize(4, 3);
    mesh.V << 0, 0, 0, scale, 0, 0, scale, scale, 0, 0, scale, 1;
    mesh.F = m.topology;
    return mesh;
}

} // namespace

TEST_CASE("dataset: write, open and load shapes as #samples by 3#V rows")
{
    test::TempDir dir;
    const Manifest m = square(3);
    writeDataset(dir / "set", m, [&](const fs::path& tmp) {
        for (int i = 0; i < 3; ++i)
            writePly(tmp / m.samples[static_cast<size_t>(i)].file, squareMesh(m, i + 1));
    });
    const Dataset d = openDataset(dir / "set");
    REQUIRE(d.manifest.samples.size() == 3);
    const Eigen::MatrixXd train = loadShapes(d, Role::Train);
    REQUIRE(train.rows() == 2);
    REQUIRE(train.cols() == 12);
    REQUIRE(train(0, 3) == Approx(2.0)); // s1: x of vertex 1
    REQUIRE(train(1, 6) == Approx(3.0)); // s2: x of vertex 2
    REQUIRE(train(1, 11) == Approx(1.0));
    REQUIRE(unflatten(train.row(1)).row(2) == Eigen::RowVector3d(3, 3, 0));
    REQUIRE(loadShapes(d, Role::Test, "skin").rows() == 1);
    REQUIRE_THROWS_WITH(loadShapes(d, Role::Test, "tongue"), Catch::Contains("no component 'tongue'"));
    // No temporary folders are left behind.
    int entries = 0;
    for (const auto& e : fs::directory_iterator(dir.path()))
        entries += e.path().filename() == "set" ? 0 : 1;
    REQUIRE(entries == 0);
}

TEST_CASE("dataset: a failure while writing leaves the old folder untouched and no temporary")
{
    test::TempDir dir;
    const Manifest m = square(1);
    writeDataset(dir / "set", m, [&](const fs::path& tmp) { writePly(tmp / "s0.ply", squareMesh(m, 1)); });
    REQUIRE_THROWS_WITH(writeDataset(dir / "set", m, [](const fs::path&) { fail("generator broke"); }), Catch::Contains("generator broke"));
    // A listed file that was never written is caught before the rename.
    REQUIRE_THROWS_WITH(writeDataset(dir / "set", square(2), [&](const fs::path& tmp) { writePly(tmp / "s0.ply", squareMesh(m, 7)); }),
        Catch::Contains("samples[1].file: 's1.ply' does not exist"));
    const Dataset d = openDataset(dir / "set");
    REQUIRE(loadMesh(d, "s0.ply").V(1, 0) == Approx(1.0));
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path()))
        ++entries;
    REQUIRE(entries == 1);
    // Replacing works and a non-dataset folder is never replaced.
    writeDataset(dir / "set", m, [&](const fs::path& tmp) { writePly(tmp / "s0.ply", squareMesh(m, 5)); });
    REQUIRE(loadMesh(openDataset(dir / "set"), "s0.ply").V(1, 0) == Approx(5.0));
    fs::create_directory(dir / "photos");
    test::writeText(dir / "photos" / "me.jpg", "x");
    REQUIRE_THROWS_WITH(writeDataset(dir / "photos", m, [](const fs::path&) {}), Catch::Contains("not a dataset"));
    REQUIRE(fs::exists(dir / "photos" / "me.jpg"));
}

TEST_CASE("dataset: missing files and meshes that do not match the topology are named")
{
    test::TempDir dir;
    const Manifest m = square(1);
    writeDataset(dir / "set", m, [&](const fs::path& tmp) { writePly(tmp / "s0.ply", squareMesh(m, 1)); });
    REQUIRE_THROWS_WITH(openDataset(dir / "nothing"), Catch::Contains("not a folder"));
    fs::remove(dir / "set" / "s0.ply");
    REQUIRE_THROWS_WITH(openDataset(dir / "set"), Catch::Contains("samples[0].file: 's0.ply' does not exist"));
    Mesh other = squareMesh(m, 1);
    other.F.row(1) << 0, 3, 2;
    writePly(dir / "set" / "s0.ply", other);
    const Dataset d = openDataset(dir / "set");
    REQUIRE_THROWS_WITH(loadMesh(d, "s0.ply"), Catch::Contains("triangle 1 (0, 3, 2) differs from the manifest's topology[1]"));
    Mesh small;
    small.V = Vertices::Zero(3, 3);
    small.F.resize(1, 3);
    small.F << 0, 1, 2;
    writePly(dir / "set" / "s0.ply", small);
    REQUIRE_THROWS_WITH(loadMesh(d, "s0.ply"), Catch::Contains("has 3 vertices, the manifest's topology has 4"));
}

TEST_CASE("dataset: a sample file that is a symbolic link out of the folder is refused and never read")
{
    test::TempDir dir;
    const Manifest m = square(2);
    writeDataset(dir / "set", m, [&](const fs::path& tmp) {
        writePly(tmp / "s0.ply", squareMesh(m, 1));
        writePly(tmp / "s1.ply", squareMesh(m, 2));
    });
    REQUIRE_NOTHROW(openDataset(dir / "set"));
    // A link to a mesh outside: refused although the mesh is valid.
    writePly(dir / "outside.ply", squareMesh(m, 3));
    fs::remove(dir / "set" / "s1.ply");
    fs::create_symlink(dir / "outside.ply", dir / "set" / "s1.ply");
    REQUIRE_THROWS_WITH(openDataset(dir / "set"), Catch::Contains("samples[1].file: 's1.ply' leads outside the dataset folder"));
    // So is a linked folder on the way; a link that stays inside is fine.
    fs::remove(dir / "set" / "s1.ply");
    fs::create_directory(dir / "elsewhere");
    writePly(dir / "elsewhere" / "s1.ply", squareMesh(m, 2));
    Manifest nested = m;
    nested.samples[1].file = "sub/s1.ply";
    writeManifest(dir / "set" / "manifest.json", nested);
    fs::create_directory_symlink(dir / "elsewhere", dir / "set" / "sub");
    REQUIRE_THROWS_WITH(openDataset(dir / "set"), Catch::Contains("'sub/s1.ply' leads outside the dataset folder"));
    fs::remove(dir / "set" / "sub");
    fs::create_directory(dir / "set" / "real");
    writePly(dir / "set" / "real" / "s1.ply", squareMesh(m, 2));
    fs::create_directory_symlink("real", dir / "set" / "sub");
    REQUIRE(openDataset(dir / "set").manifest.samples[1].file == "sub/s1.ply");
}

// Tests of registration/import_scans: a folder of scans with one bad among them becomes a dataset
// in the template's topology, the bad scan reported with its reason.
#include "registration/import_scans.h"

#include "core/error.h"
#include "dataset/import_meshes.h"
#include "io/mesh_io.h"
#include "registration/surface_query.h"
#include "test_common.h"
#include "test_head.h"

#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>

using namespace facesketch;
using namespace facesketch::registration;
namespace fs = std::filesystem;

namespace {

// A template dataset of two training heads (tests/registration/test_head.h), in cm.
dataset::Dataset writeTemplate(const fs::path& folder)
{
    const Mesh a = test::makeHead(3), b = test::makeHead(3, 4.0);
    dataset::Manifest m;
    m.units = "cm";
    m.vertexCount = static_cast<int>(a.V.rows());
    m.topology = a.F;
    m.components = { { "skin", 0, m.vertexCount } };
    m.landmarks = test::headLandmarks(a);
    m.samples = { { "a", "faces/a.ply", dataset::Role::Train }, { "b", "faces/b.ply", dataset::Role::Train } };
    dataset::writeDataset(folder, m, [&](const fs::path& tmp) {
        fs::create_directories(tmp / "faces");
        writeMesh(tmp / "faces/a.ply", Mesh { a.V / 10.0, a.F });
        writeMesh(tmp / "faces/b.ply", Mesh { b.V / 10.0, b.F });
    });
    return dataset::openDataset(folder);
}

void writePoints(const fs::path& path, const FeaturePoints& points)
{
    nlohmann::json doc = nlohmann::json::object();
    for (const auto& [name, p] : points)
        doc[name] = { p.x(), p.y(), p.z() };
    test::writeText(path, doc.dump());
}

} // namespace

TEST_CASE("meanFace: the mean of the training faces in the dataset's topology")
{
    test::TempDir dir;
    const dataset::Dataset ds = writeTemplate(dir / "template");
    const Mesh mean = meanFace(ds);
    const Mesh a = dataset::loadMesh(ds, "faces/a.ply"), b = dataset::loadMesh(ds, "faces/b.ply");
    REQUIRE((mean.V - 0.5 * (a.V + b.V)).cwiseAbs().maxCoeff() < 1e-12);
    REQUIRE(mean.F == ds.manifest.topology);
}

TEST_CASE("importScans: registers every good scan into the template's topology, reports the bad ones")
{
    test::TempDir dir;
    const dataset::Dataset templ = writeTemplate(dir / "template");
    fs::create_directories(dir / "scans");
    // Scans in mm: two good ones of another topology, one without points, one with a point off it.
    for (const auto& [name, cheek] : std::vector<std::pair<std::string, double>> { { "anna", 6.0 }, { "bert", -3.0 } }) {
        writeMesh(dir / "scans" / (name + ".ply"), test::makeHead(5, cheek));
        writePoints(dir / "scans" / (name + ".points.json"), test::headPoints(cheek));
    }
    writeMesh(dir / "scans/carl.obj", test::makeHead(4));
    writeMesh(dir / "scans/dora.ply", test::makeHead(4));
    FeaturePoints off = test::headPoints();
    off["prn"].z() += 20.0;
    writePoints(dir / "scans/dora.points.json", off);
    test::writeText(dir / "scans/notes.txt", "not a scan");

    ScanImportOptions options;
    options.registration.mapWidth = options.registration.mapHeight = 256;
    options.threads = 1; // progress after every scan, in file order
    std::vector<std::string> seen;
    options.progress = [&](int done, int total, const std::string& name) {
        REQUIRE(total == 4);
        REQUIRE(done == static_cast<int>(seen.size()) + 1);
        seen.push_back(name);
    };
    const ScanImport result = importScans(dir / "scans", templ, dir / "out", options);
    REQUIRE(seen == std::vector<std::string> { "anna.ply", "bert.ply", "carl.obj", "dora.ply" });
    REQUIRE(result.failures.size() == 2);
    REQUIRE_THAT(result.failures[0].reason, Catch::Contains("carl.obj: no feature points"));
    REQUIRE_THAT(result.failures[1].reason, Catch::Contains("dora.ply: feature point 'prn'"));

    const dataset::Dataset out = dataset::openDataset(dir / "out");
    REQUIRE(out.manifest.units == "cm");
    REQUIRE(out.manifest.vertexCount == templ.manifest.vertexCount);
    REQUIRE(out.manifest.landmarks == templ.manifest.landmarks);
    REQUIRE(out.manifest.samples.size() == 2);
    REQUIRE(out.manifest.samples[0].name == "anna");
    REQUIRE(out.manifest.samples[1].name == "bert");
    const std::vector<dataset::Role> roles = dataset::shuffledRoles(2, options.seed);
    REQUIRE(out.manifest.samples[0].role == roles[0]);
    REQUIRE(out.manifest.samples[1].role == roles[1]);
    // The registered face lies on its scan (in the dataset's cm) over the face.
    const Mesh anna = dataset::loadMesh(out, "faces/anna.ply");
    Mesh scanCm = test::makeHead(5, 6.0);
    scanCm.V /= 10.0;
    const SurfaceQuery surface(scanCm);
    for (Eigen::Index v = 0; v < anna.V.rows(); ++v) {
        const Eigen::Vector3d u = anna.V.row(v).normalized();
        if (u.z() > 0.6 && std::abs(u.y()) < 0.5)
            REQUIRE(surface.closest(anna.V.row(v).transpose()).distance < 0.015); // 0.15 mm, as registerScan's own test
    }

    // On several threads: the same failures in file order, the same bytes written, and the
    // progress ends at every scan done.
    options.threads = 3;
    int last = 0;
    options.progress = [&](int done, int total, const std::string&) {
        REQUIRE(total == 4);
        REQUIRE(done >= last);
        last = done;
    };
    const ScanImport threaded = importScans(dir / "scans", templ, dir / "out3", options);
    REQUIRE(last == 4);
    REQUIRE(threaded.failures.size() == 2);
    for (size_t k = 0; k < 2; ++k)
        REQUIRE(threaded.failures[k].reason == result.failures[k].reason);
    for (const char* file : { "manifest.json", "faces/anna.ply", "faces/bert.ply" })
        REQUIRE(test::readBytes(dir / "out3" / file) == test::readBytes(dir / "out" / file));
}

TEST_CASE("importScans: nothing is written when no scan registers, and the reasons are listed")
{
    test::TempDir dir;
    const dataset::Dataset templ = writeTemplate(dir / "template");
    fs::create_directories(dir / "scans");
    writeMesh(dir / "scans/carl.obj", test::makeHead(3));
    REQUIRE_THROWS_WITH(importScans(dir / "scans", templ, dir / "out"),
        Catch::Contains("no scan registered") && Catch::Contains("carl.obj: no feature points"));
    REQUIRE_FALSE(fs::exists(dir / "out"));
    fs::create_directories(dir / "empty");
    REQUIRE_THROWS_WITH(importScans(dir / "empty", templ, dir / "out"), Catch::Contains("no .obj or .ply scans"));
    ScanImportOptions bad;
    bad.units = "inch";
    REQUIRE_THROWS_WITH(importScans(dir / "scans", templ, dir / "out", bad), Catch::Contains("units 'inch'"));
}

// `import ict-facekit` on the real ICT Face Model Light. The model is never part of the
// repository: tests read it from $FACESKETCH_ICT_DIR, else ../shared/datasets/ict-facekit
// beside the source tree, and report themselves SKIPPED (a visible warning) when it is absent.
#include "dataset/import_ict.h"
#include "core/error.h"
#include "dataset/dataset.h"
#include "dataset/synth/pose_recipes.h"
#include "ict_fixtures.h"
#include "io/mesh_io.h"
#include "test_common.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

using namespace facesketch;
using namespace facesketch::dataset;
namespace fs = std::filesystem;
using test::ictDir;
using test::isEdgePath;
using test::isLoop;

namespace {

fs::path recipes()
{
    const char* source = std::getenv("FACESKETCH_SOURCE_DIR");
    return fs::path(source ? source : ".") / "assets" / "ict-poses.json";
}

std::string bytes(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST_CASE("import_ict: the pose recipes name the 36 poses of the synthetic set")
{
    const IctPoseRecipes r = readIctPoseRecipes(recipes());
    REQUIRE(r.size() == poseRecipes().size());
    for (size_t i = 0; i < r.size(); ++i)
        REQUIRE(r[i].first == poseRecipes()[i].name);
    REQUIRE(r[0].second.empty()); // neutral
    test::TempDir dir;
    test::writeText(dir / "bad.json", R"({"smile": {"mouthSmile_L": "lots"}})");
    REQUIRE_THROWS_WITH(readIctPoseRecipes(dir / "bad.json"), Catch::Contains("bad.json: smile.mouthSmile_L"));
}

TEST_CASE("import_ict: identity coefficients are deterministic standard normal draws")
{
    const Eigen::VectorXd a = ictCoefficients(5, 3, 100);
    REQUIRE(a == ictCoefficients(5, 3, 100));
    REQUIRE(a != ictCoefficients(5, 4, 100));
    REQUIRE(a != ictCoefficients(6, 3, 100));
    double sum = 0, sq = 0;
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
        const Eigen::VectorXd c = ictCoefficients(1, i, 100);
        sum += c.sum();
        sq += c.squaredNorm();
    }
    const double mean = sum / (100.0 * n), var = sq / (100.0 * n) - mean * mean;
    REQUIRE(std::abs(mean) < 0.01);
    REQUIRE(std::abs(var - 1) < 0.02);
}

TEST_CASE("import_ict: same seed gives byte-identical datasets, another seed differs")
{
    REQUIRE_ICT_OR_SKIP();
    test::TempDir dir;
    IctOptions o;
    o.identities = 3;
    o.region = IctRegion::NarrowFace;
    o.seed = 11;
    writeIctDataset(ictDir(), dir / "a", o);
    writeIctDataset(ictDir(), dir / "b", o);
    o.seed = 12;
    writeIctDataset(ictDir(), dir / "c", o);
    int files = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir / "a"))
        if (e.is_regular_file()) {
            const fs::path rel = fs::relative(e.path(), dir / "a");
            REQUIRE(bytes(e.path()) == bytes(dir / "b" / rel));
            ++files;
        }
    REQUIRE(files == 4);
    REQUIRE(bytes(dir / "a" / "faces" / "face_0001.ply") != bytes(dir / "c" / "faces" / "face_0001.ply"));
}

TEST_CASE("import_ict: poses move what they should")
{
    REQUIRE_ICT_OR_SKIP();
    test::TempDir dir;
    IctOptions o;
    o.identities = 1;
    o.poses = true;
    o.mouth = true;
    o.recipes = recipes();
    const Manifest m = writeIctDataset(ictDir(), dir / "posed", o);
    REQUIRE(m.poses.size() == 36);
    const Dataset d = openDataset(dir / "posed");
    auto pose = [&](const std::string& name) { return loadMesh(d, fs::path("poses") / "face_0000" / (name + ".ply")).V; };
    const Vertices neutral = loadMesh(d, d.manifest.samples[0].file).V;
    const auto& L = m.landmarks;
    REQUIRE((pose("neutral") - neutral).cwiseAbs().maxCoeff() < 1e-4);
    // Jaw open: the chin drops by more than a centimetre; the nose stays.
    const Vertices jaw = pose("jaw_open");
    REQUIRE(neutral(L.at("gn"), 1) - jaw(L.at("gn"), 1) > 10);
    REQUIRE((jaw.row(L.at("prn")) - neutral.row(L.at("prn"))).norm() < 1);
    // ... and carries the whole tongue with it, as it does the lower teeth.
    const Component& tongue = *m.component("tongue");
    double least = 1e9;
    for (int v = tongue.begin; v < tongue.end; ++v)
        least = std::min(least, (jaw.row(v) - neutral.row(v)).norm());
    INFO("the tongue vertex that jaw_open moves least moves " << least << " mm");
    REQUIRE(least > 10);
    // Blink: upper lids come down to the lower lids.
    const Vertices blink = pose("blink");
    for (const char* s : { "_l", "_r" }) {
        const double open = neutral(L.at(std::string("ps") + s), 1) - neutral(L.at(std::string("pi") + s), 1);
        const double shut = blink(L.at(std::string("ps") + s), 1) - blink(L.at(std::string("pi") + s), 1);
        REQUIRE(shut < 0.3 * open);
    }
    // Smile: both mouth corners rise and the mouth widens.
    const Vertices smile = pose("smile_closed");
    REQUIRE(smile(L.at("ch_l"), 1) > neutral(L.at("ch_l"), 1) + 2);
    REQUIRE(smile(L.at("ch_r"), 1) > neutral(L.at("ch_r"), 1) + 2);
    REQUIRE(smile(L.at("ch_l"), 0) - smile(L.at("ch_r"), 0) > neutral(L.at("ch_l"), 0) - neutral(L.at("ch_r"), 0));
    // Brow raise lifts the brows; one-sided smile moves only its own corner.
    REQUIRE(pose("brow_raise")(L.at("os_l"), 1) > neutral(L.at("os_l"), 1) + 2);
    const Vertices left = pose("smile_left");
    REQUIRE(left(L.at("ch_l"), 1) - neutral(L.at("ch_l"), 1) > 2);
    REQUIRE(std::abs(left(L.at("ch_r"), 1) - neutral(L.at("ch_r"), 1)) < 1);
}

TEST_CASE("import_ict: bad model files name the file and line and write nothing")
{
    REQUIRE_ICT_OR_SKIP();
    test::TempDir dir;
    const fs::path model = dir / "ict" / "FaceXModel";
    fs::create_directories(model);
    fs::create_symlink(fs::absolute(ictDir() / "FaceXModel" / "generic_neutral_mesh.obj"), model / "generic_neutral_mesh.obj");
    IctOptions o;
    o.identities = 2;
    auto refused = [&](const std::string& expected) {
        REQUIRE_THROWS_WITH(writeIctDataset(dir / "ict", dir / "out", o), Catch::Contains(expected));
        REQUIRE(!fs::exists(dir / "out"));
    };
    refused("no identity000.obj");
    test::writeText(model / "identity000.obj", "# modes\nv 1 2 3\nv 1 nan 3\n");
    refused("identity000.obj:3: vertex coordinate y is nan");
    test::writeText(model / "identity000.obj", "v 1 2 3\nv 1 2\n");
    refused("identity000.obj:2: vertex coordinate z is missing");
    test::writeText(model / "identity000.obj", "v 1 2 3\nv 1 2 3\n");
    refused("identity000.obj: has 2 vertices, generic_neutral_mesh.obj has 26719");
    REQUIRE_THROWS_WITH(writeIctDataset(dir / "nothing", dir / "out", o), Catch::Contains("nothing: does not exist"));
    o.poses = true;
    o.recipes = dir / "no-recipes.json";
    refused("no-recipes.json: cannot open");
}

TEST_CASE("import_ict: --vertices keeps every label and contour edge on the coarser topology")
{
    REQUIRE_ICT_OR_SKIP();
    test::TempDir dir;
    IctOptions o;
    o.identities = 2;
    const Manifest full = writeIctDataset(ictDir(), dir / "full", o);
    o.vertices = 2500;
    const Manifest coarse = writeIctDataset(ictDir(), dir / "coarse", o);
    INFO(coarse.vertexCount << " vertices");
    REQUIRE(std::abs(coarse.vertexCount - 2500) < 250);
    REQUIRE(coarse.landmarks.size() == full.landmarks.size());
    REQUIRE(coarse.mpeg4.size() == full.mpeg4.size());
    for (const auto& [name, path] : coarse.contours) {
        INFO(name);
        REQUIRE(path.size() == full.contours.at(name).size());
        REQUIRE(isEdgePath(coarse.topology, path, isLoop(name)));
    }
    // Labelled vertices sit where they sat before simplification.
    const Dataset a = openDataset(dir / "full"), b = openDataset(dir / "coarse");
    const Vertices va = loadMesh(a, a.manifest.samples[1].file).V, vb = loadMesh(b, b.manifest.samples[1].file).V;
    for (const auto& [name, v] : full.landmarks)
        REQUIRE((va.row(v) - vb.row(coarse.landmarks.at(name))).norm() < 1e-4);
}

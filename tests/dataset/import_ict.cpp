// `import ict-facekit` on the real ICT Face Model Light. The model is never part of the
// repository: tests read it from $FACESKETCH_ICT_DIR, else ../shared/datasets/ict-facekit
// beside the source tree, and report themselves SKIPPED (a visible warning) when it is absent.
#include "dataset/import_ict.h"
#include "core/error.h"
#include "dataset/dataset.h"
#include "dataset/face_poses.h"
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

namespace {

fs::path ictDir()
{
    if (const char* dir = std::getenv("FACESKETCH_ICT_DIR"))
        return dir;
    const char* source = std::getenv("FACESKETCH_SOURCE_DIR");
    return fs::path(source ? source : ".") / ".." / "shared" / "datasets" / "ict-facekit";
}

bool haveIct()
{
    return fs::is_regular_file(ictDir() / "FaceXModel" / "generic_neutral_mesh.obj");
}

#define REQUIRE_ICT_OR_SKIP()                                                                                                              \
    if (!haveIct()) {                                                                                                                      \
        WARN("SKIPPED: no ICT-FaceKit at " << ictDir().string() << " (set FACESKETCH_ICT_DIR); test not run");                             \
        return;                                                                                                                            \
    }

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

// Contours that close on themselves (docs/dataset-format.md).
bool isLoop(const std::string& contour)
{
    return contour.rfind("eye_socket", 0) == 0 || contour.rfind("nostril", 0) == 0;
}

bool isEdgePath(const Triangles& F, const std::vector<int>& path, bool closed)
{
    std::set<std::pair<int, int>> edges;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k)
            edges.insert({ std::min(F(f, k), F(f, (k + 1) % 3)), std::max(F(f, k), F(f, (k + 1) % 3)) });
    const size_t n = path.size();
    for (size_t i = 0; i + (closed ? 0 : 1) < n; ++i) {
        const int a = path[i], b = path[(i + 1) % n];
        if (!edges.count({ std::min(a, b), std::max(a, b) }))
            return false;
    }
    return true;
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

TEST_CASE("import_ict: 10 identities put every landmark on its feature, in mm, with edge-path contours")
{
    REQUIRE_ICT_OR_SKIP();
    test::TempDir dir;
    IctOptions o;
    o.identities = 10;
    o.eyes = o.mouth = true;
    const Manifest m = writeIctDataset(ictDir(), dir / "ict", o);
    const Dataset d = openDataset(dir / "ict");
    REQUIRE(d.manifest.samples.size() == 10);
    REQUIRE(d.manifest.units == "mm");
    const Component& skin = *d.manifest.component("skin");
    REQUIRE(skin.size() == 9409);
    for (const char* c : { "eye_left", "eye_right", "teeth_upper", "teeth_lower", "gums", "tongue" })
        REQUIRE(d.manifest.component(c));
    REQUIRE(d.manifest.mpeg4.size() == 46); // thesis 5.2: 40 skin, 4 tongue, 2 lower teeth
    const Component& tongue = *d.manifest.component("tongue");
    for (const char* p : { "6.1", "6.2", "6.3", "6.4" })
        REQUIRE(tongue.contains(m.mpeg4.at(p)));
    for (const auto& [name, path] : m.contours) {
        INFO(name);
        REQUIRE(isEdgePath(m.topology, path, isLoop(name)));
        REQUIRE(std::set<int>(path.begin(), path.end()).size() == path.size()); // no vertex twice
        for (int v : path)
            REQUIRE(skin.contains(v));
    }
    REQUIRE(m.contours.count("nostril_l"));
    REQUIRE(m.contours.count("nostril_r"));
    // The cavity inside each rim is hidden from contour candidates; the rims themselves are not.
    std::set<int> hiddenSkin;
    for (int v : m.excluded)
        if (skin.contains(v))
            hiddenSkin.insert(v);
    for (const char* ring : { "nostril_l", "nostril_r" })
        for (int v : m.contours.at(ring))
            REQUIRE(!hiddenSkin.count(v));
    const std::set<int> all(m.excluded.begin(), m.excluded.end());
    REQUIRE(all.size() == m.excluded.size());
    const auto& L = m.landmarks;
    std::vector<double> heights;
    for (const Sample& s : d.manifest.samples) {
        const Mesh mesh = loadMesh(d, s.file); // validates: finite, topology
        const Vertices& V = mesh.V;
        INFO(s.name);
        REQUIRE(V.allFinite());
        const double height = (V.row(L.at("n")) - V.row(L.at("gn"))).norm();
        heights.push_back(height);
        REQUIRE(height > 100);
        REQUIRE(height < 140);
        // prn: the most forward skin vertex lies within 3 mm of it. "Forward" is the face's own:
        // real heads are pitched differently, so it is measured along (ex_l - ex_r) x (n - gn).
        const Eigen::RowVector3d across = V.row(L.at("ex_l")) - V.row(L.at("ex_r"));
        const Eigen::RowVector3d up = V.row(L.at("n")) - V.row(L.at("gn"));
        const Eigen::RowVector3d forward = across.cross(up).normalized();
        REQUIRE(forward(2) > 0.9);
        Eigen::Index front = 0;
        (V.middleRows(skin.begin, skin.size()) * forward.transpose()).maxCoeff(&front);
        const double apart = (V.row(front) - V.row(L.at("prn"))).norm();
        // ICT's vertices along the tip are about 3 mm apart, so the bar is 3 mm or one edge at prn.
        double edge = 0;
        for (Eigen::Index f = 0; f < m.topology.rows(); ++f)
            for (int k = 0; k < 3; ++k)
                if (m.topology(f, k) == L.at("prn"))
                    for (int j = 1; j < 3; ++j)
                        edge = std::max(edge, (V.row(L.at("prn")) - V.row(m.topology(f, (k + j) % 3))).norm());
        INFO("prn is " << apart << " mm from the most forward vertex " << front << "; longest edge at prn " << edge);
        REQUIRE(apart < std::max(3.0, 1.05 * edge));
        // ch: the outer lip corners, the lip contour vertices of extreme x.
        for (const char* lip : { "lip_upper_outer", "lip_lower_outer" }) {
            double minX = 1e9, maxX = -1e9;
            for (int v : m.contours.at(lip)) {
                minX = std::min(minX, V(v, 0));
                maxX = std::max(maxX, V(v, 0));
            }
            REQUIRE(V(L.at("ch_l"), 0) > maxX - 1);
            REQUIRE(V(L.at("ch_r"), 0) < minX + 1);
        }
        // Sides and order of the eye corners; face's left is +x.
        REQUIRE(V(L.at("ex_l"), 0) > V(L.at("en_l"), 0));
        REQUIRE(V(L.at("en_l"), 0) > 0);
        REQUIRE(V(L.at("en_r"), 0) < 0);
        REQUIRE(V(L.at("ex_r"), 0) < V(L.at("en_r"), 0));
        // Plausible sizes (Farkas' adult norms give about 35 mm nose width, 90 mm biocular width).
        const double nose = V(L.at("al_l"), 0) - V(L.at("al_r"), 0);
        const double eyes = V(L.at("ex_l"), 0) - V(L.at("ex_r"), 0);
        REQUIRE(nose > 25);
        REQUIRE(nose < 50);
        REQUIRE(eyes > 75);
        REQUIRE(eyes < 110);
        // Profile order along the midline.
        REQUIRE(V(L.at("g"), 1) > V(L.at("n"), 1));
        REQUIRE(V(L.at("prn"), 1) > V(L.at("sn"), 1));
        REQUIRE(V(L.at("sn"), 1) > V(L.at("ls"), 1));
        REQUIRE(V(L.at("ls"), 1) > V(L.at("sto"), 1));
        REQUIRE(V(L.at("sto"), 1) > V(L.at("li"), 1));
        REQUIRE(V(L.at("li"), 1) > V(L.at("sl"), 1));
        REQUIRE(V(L.at("sl"), 1) > V(L.at("pg"), 1));
        REQUIRE(V(L.at("pg"), 1) > V(L.at("gn"), 1));
        REQUIRE(V(L.at("ps_l"), 1) > V(L.at("pi_l"), 1));
        REQUIRE(V(L.at("os_l"), 1) > V(L.at("ps_l"), 1));
        // Nostril rings: each around its own nostril, below prn and beside sn, medial to its sbal.
        // ICT's nostril openings run up to about 21 mm forward from sbal (250 identities, seed 1).
        for (int side : { 1, -1 }) {
            const std::string sfx = side > 0 ? "_l" : "_r";
            const std::vector<int>& ring = m.contours.at("nostril" + sfx);
            Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
            double far = 0;
            for (int v : ring) {
                centre += V.row(v) / static_cast<double>(ring.size());
                far = std::max(far, (V.row(v) - V.row(L.at("sbal" + sfx))).norm());
            }
            INFO("nostril" << sfx << ": " << ring.size() << " vertices, centroid (" << centre << "), farthest " << far << " mm from sbal");
            REQUIRE(ring.size() >= 12);
            REQUIRE(side * centre(0) > 2);
            REQUIRE(side * centre(0) < side * V(L.at("sbal" + sfx), 0));
            REQUIRE(centre(1) > V(L.at("sn"), 1));
            REQUIRE(centre(1) < V(L.at("prn"), 1));
            REQUIRE(far < 25);
            int hiddenNear = 0;
            for (int v : hiddenSkin)
                if ((V.row(v) - V.row(L.at("sbal" + sfx))).norm() < 25 && side * V(v, 0) > 0)
                    ++hiddenNear;
            REQUIRE(hiddenNear >= 10);
        }
        for (int v : hiddenSkin) // only the nostril cavities are hidden skin
            REQUIRE(std::min((V.row(v) - V.row(L.at("sbal_l"))).norm(), (V.row(v) - V.row(L.at("sbal_r"))).norm()) < 25);
        // Tongue: 6.1 the most forward tongue vertex, 6.2 on the midline behind it and above the
        // borders, 6.3 (left) at +x and 6.4 (right) at -x.
        const Eigen::Index first = tongue.begin;
        Eigen::Index ahead = 0;
        V.middleRows(first, tongue.size()).col(2).maxCoeff(&ahead);
        const double tipBehind = V(first + ahead, 2) - V(m.mpeg4.at("6.1"), 2);
        INFO("6.1 is " << tipBehind << " mm behind the most forward tongue vertex");
        REQUIRE(tipBehind < 1);
        REQUIRE(std::abs(V(m.mpeg4.at("6.1"), 0)) < 2);
        REQUIRE(std::abs(V(m.mpeg4.at("6.2"), 0)) < 2);
        REQUIRE(V(m.mpeg4.at("6.1"), 2) - V(m.mpeg4.at("6.2"), 2) > 15);
        REQUIRE(V(m.mpeg4.at("6.3"), 0) > 15);
        REQUIRE(V(m.mpeg4.at("6.4"), 0) < -15);
        for (const char* border : { "6.3", "6.4" })
            REQUIRE(V(m.mpeg4.at("6.2"), 1) > V(m.mpeg4.at(border), 1));
    }
    // Distinct identities.
    REQUIRE(*std::max_element(heights.begin(), heights.end()) - *std::min_element(heights.begin(), heights.end()) > 1);
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

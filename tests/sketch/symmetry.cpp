// The vertex mirror map, found and verified on the synthetic topology and an ICT-FaceKit import.
#include "sketch/symmetry.h"

#include "core/error.h"
#include "dataset/import_ict.h"
#include "model/trained.h"

#include <cstdlib>

using namespace facesketch;
using namespace facesketch::sketch;
namespace fs = std::filesystem;

namespace {

// The mean skin of a dataset's train faces, on the skin topology.
Mesh meanSkin(const dataset::Dataset& d)
{
    const Eigen::MatrixXd rows = dataset::loadShapes(d, dataset::Role::Train, "skin");
    Mesh mesh;
    mesh.V = dataset::unflatten(rows.colwise().mean());
    mesh.F = model::skinTriangles(d.manifest);
    return mesh;
}

void requireGoodMap(const MirrorMap& map, const Mesh& face, int maxUnpaired)
{
    const MirrorCheck& c = map.check();
    INFO("plane x = " << c.planeX << " mm, mean edge " << c.meanEdge << " mm, worst pair " << c.maxDistance << " mm, mean "
                      << c.meanDistance << " mm, " << c.selfPaired << " on the plane, " << c.unpaired << " unpaired, " << c.labelledPairs
                      << " labelled pairs");
    REQUIRE(map.size() == face.V.rows());
    REQUIRE(c.unpaired <= maxUnpaired);
    for (Eigen::Index v = 0; v < map.size(); ++v)
        if (map.partner(static_cast<std::uint32_t>(v)) != MirrorMap::kNone)
            REQUIRE(map.partner(map.partner(static_cast<std::uint32_t>(v))) == static_cast<std::uint32_t>(v));
    REQUIRE(c.labelledPairs >= 4);
    REQUIRE(c.maxDistance <= c.meanEdge);
    REQUIRE(c.selfPaired > 0);
    REQUIRE(c.selfPaired < face.V.rows() / 4);
    // Vertices on the plane pair with themselves; the others with a vertex on the far side.
    for (Eigen::Index v = 0; v < map.size(); ++v) {
        const std::uint32_t p = map.partner(static_cast<std::uint32_t>(v));
        if (p == MirrorMap::kNone)
            continue;
        const double side = face.V(v, 0) - c.planeX, other = face.V(p, 0) - c.planeX;
        if (std::abs(side) > c.meanEdge)
            REQUIRE(side * other < 0);
    }
}

} // namespace

TEST_CASE("symmetry: the synthetic topology's mirror map is an involution that swaps the labelled sides")
{
    const auto& t = test::trainedSynth();
    const Mesh face = meanSkin(t.dataset);
    const dataset::Component& skin = *t.dataset.manifest.component("skin");
    const auto landmarks = skinLandmarks(t.dataset.manifest.landmarks, skin.begin, skin.end);
    const MirrorMap map = MirrorMap::find(face, landmarks, "synthetic mean");
    requireGoodMap(map, face, 0); // the generator's topology is exactly symmetric
    REQUIRE(map.partner(static_cast<std::uint32_t>(landmarks.at("ex_l"))) == static_cast<std::uint32_t>(landmarks.at("ex_r")));
    REQUIRE(map.partner(static_cast<std::uint32_t>(landmarks.at("prn"))) == static_cast<std::uint32_t>(landmarks.at("prn")));
    const Eigen::Vector3d n = map.check().normal, p = (map.check().planeX + 7) * n + Eigen::Vector3d(0, 2, 3).cross(n);
    REQUIRE(n.x() > 0.999); // the generator's faces look down +z, symmetric about a plane x = c
    REQUIRE(map.mirror(p).isApprox(p - 14 * n));
    REQUIRE(map.mirror(map.mirror(p)).isApprox(p));
}

TEST_CASE("symmetry: an asymmetric face or a wrong label is refused, naming the vertex")
{
    const auto& t = test::trainedSynth();
    Mesh face = meanSkin(t.dataset);
    const dataset::Component& skin = *t.dataset.manifest.component("skin");
    auto landmarks = skinLandmarks(t.dataset.manifest.landmarks, skin.begin, skin.end);
    // A wrong label: ex_r moved to en_r.
    auto wrong = landmarks;
    wrong["ex_r"] = landmarks.at("en_r");
    REQUIRE_THROWS_WITH(MirrorMap::find(face, wrong, "m"), Catch::Contains("labelled pair"));
    // One side pushed out by 5 mm.
    for (Eigen::Index v = 0; v < face.V.rows(); ++v)
        if (face.V(v, 0) > 10)
            face.V(v, 0) += 5;
    REQUIRE_THROWS_WITH(MirrorMap::find(face, landmarks, "bent"), Catch::StartsWith("bent: "));
    REQUIRE_THROWS_WITH(MirrorMap::find(Mesh {}, landmarks, "nothing"), Catch::Contains("nothing: no mesh"));
}

TEST_CASE("symmetry: an ICT-FaceKit import is refused: its labelled pairs do not swap")
{
    const char* env = std::getenv("FACESKETCH_ICT_DIR");
    const char* source = std::getenv("FACESKETCH_SOURCE_DIR");
    const fs::path ict = env ? fs::path(env) : fs::path(source ? source : ".") / ".." / "shared" / "datasets" / "ict-facekit";
    if (!fs::is_regular_file(ict / "FaceXModel" / "generic_neutral_mesh.obj")) {
        WARN("SKIPPED: no ICT-FaceKit at " << ict.string() << " (set FACESKETCH_ICT_DIR); test not run");
        return;
    }
    test::TempDir dir;
    dataset::IctOptions o;
    o.identities = 10;
    dataset::writeIctDataset(ict, dir / "ict", o);
    const dataset::Dataset d = dataset::openDataset(dir / "ict");
    const Mesh face = meanSkin(d);
    const dataset::Component& skin = *d.manifest.component("skin");
    // Measured: the ICT face region is not mirror-symmetric vertex for vertex. About 4% of its
    // vertices have no vertex within half their edge length of their mirror image, and some
    // labelled left/right landmark pairs do not swap under the nearest-vertex map, so the map is
    // refused (and the symmetry option with it) rather than mirroring onto wrong vertices.
    REQUIRE_THROWS_WITH(MirrorMap::find(face, skinLandmarks(d.manifest.landmarks, skin.begin, skin.end), "ICT mean"),
        Catch::StartsWith("ICT mean: the labelled pair") && Catch::Contains("does not map onto itself"));
}

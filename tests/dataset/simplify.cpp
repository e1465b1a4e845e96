// Shared-topology simplification: about N vertices, every labelled vertex kept, contours still
// edge paths, the same subset in every sample.
#include "dataset/simplify.h"
#include "core/error.h"
#include "dataset/dataset.h"
#include "dataset/synth/face_generator.h"
#include "dataset/synth/face_params.h"
#include "dataset/synth/synth_dataset.h"
#include "io/mesh_io.h"
#include "test_common.h"

#include <set>

using namespace facesketch;
using namespace facesketch::dataset;
namespace fs = std::filesystem;

namespace {

std::set<std::pair<int, int>> edgeSet(const Triangles& F)
{
    std::set<std::pair<int, int>> edges;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = F(f, k), b = F(f, (k + 1) % 3);
            edges.insert({ std::min(a, b), std::max(a, b) });
        }
    return edges;
}

} // namespace

TEST_CASE("simplify: about N vertices, every labelled vertex kept, contours still edge paths")
{
    const FaceTopology topology = buildFaceTopology(Resolution::High);
    const Manifest& m = topology.labels;
    const Vertices V = synthesizeFace(topology, sampleFaceParams(1, 0));
    for (int target : { 1500, 3000 }) {
        const Simplification s = simplifyTopology(V, m, target);
        INFO("target " << target << ", got " << s.kept.size() << " of " << m.vertexCount);
        REQUIRE(std::abs(static_cast<int>(s.kept.size()) - target) < target / 10);
        REQUIRE(std::is_sorted(s.kept.begin(), s.kept.end()));
        const Manifest out = simplifyManifest(m, s);
        validateManifest(out, "simplified");
        REQUIRE(out.vertexCount == static_cast<int>(s.kept.size()));
        for (const auto& [name, v] : m.landmarks)
            REQUIRE(s.kept[static_cast<size_t>(out.landmarks.at(name))] == v);
        for (const auto& [name, v] : m.mpeg4)
            REQUIRE(s.kept[static_cast<size_t>(out.mpeg4.at(name))] == v);
        const auto before = edgeSet(m.topology), after = edgeSet(out.topology);
        for (const auto& [name, path] : m.contours) {
            const auto& newPath = out.contours.at(name);
            REQUIRE(newPath.size() == path.size());
            for (size_t i = 0; i < path.size(); ++i)
                REQUIRE(s.kept[static_cast<size_t>(newPath[i])] == path[i]);
            for (size_t i = 0; i + 1 < path.size(); ++i) {
                const std::pair<int, int> e { std::min(path[i], path[i + 1]), std::max(path[i], path[i + 1]) };
                if (!before.count(e))
                    continue; // not an edge in the original either
                INFO(name << " edge " << i);
                REQUIRE(after.count({ std::min(newPath[i], newPath[i + 1]), std::max(newPath[i], newPath[i + 1]) }));
            }
        }
        for (const Component& c : out.components)
            REQUIRE(c.size() > 0);
    }
}

TEST_CASE("simplify: a dataset keeps the same vertex subset in every sample and pose")
{
    test::TempDir dir;
    SynthOptions o;
    o.identities = 3;
    o.poses = true;
    o.poseIdentities = 1;
    o.threads = 1;
    writeSynthDataset(dir / "full", o);
    const int n = simplifyDataset(dir / "full", dir / "coarse", 400);
    const Dataset full = openDataset(dir / "full"), coarse = openDataset(dir / "coarse");
    REQUIRE(coarse.manifest.vertexCount == n);
    REQUIRE(n < full.manifest.vertexCount);
    REQUIRE(coarse.manifest.poses.size() == full.manifest.poses.size());
    // The subset simplifyDataset used: the simplification of the mean of the samples.
    Vertices mean = Vertices::Zero(full.manifest.vertexCount, 3);
    for (const Sample& sample : full.manifest.samples)
        mean += loadMesh(full, sample.file).V;
    mean /= static_cast<double>(full.manifest.samples.size());
    const std::vector<int> subset = simplifyTopology(mean, full.manifest, 400).kept;
    REQUIRE(static_cast<int>(subset.size()) == n);
    std::vector<fs::path> files;
    for (const Sample& s : full.manifest.samples)
        files.push_back(s.file);
    for (const Pose& p : full.manifest.poses)
        files.push_back(p.file);
    for (const fs::path& file : files) {
        const Vertices a = loadMesh(full, file).V, b = loadMesh(coarse, file).V;
        for (Eigen::Index i = 0; i < b.rows(); ++i)
            REQUIRE((a.row(subset[static_cast<size_t>(i)]) - b.row(i)).norm() < 1e-4);
    }
}

TEST_CASE("simplify: bad targets and mismatched references are refused")
{
    const FaceTopology topology = buildFaceTopology(Resolution::Low);
    const Vertices V = synthesizeFace(topology, sampleFaceParams(1, 0));
    REQUIRE_THROWS_WITH(simplifyTopology(V, topology.labels, 3), Catch::Contains("--vertices 3"));
    REQUIRE_THROWS_WITH(simplifyTopology(V.topRows(10), topology.labels, 100), Catch::Contains("10 vertices"));
    // A target above the vertex count keeps everything.
    const Simplification all = simplifyTopology(V, topology.labels, 1000000);
    REQUIRE(static_cast<int>(all.kept.size()) == topology.labels.vertexCount);
}

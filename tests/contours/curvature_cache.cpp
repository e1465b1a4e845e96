// Tests of contours/curvature_cache: a second run reads the file and gives the same cloud; other
// faces, a corrupt or truncated file are recomputed, never trusted.
#include "contours/curvature_cache.h"

#include "contours/candidates_gpu.h"
#include "geometry/mesh_batch.h"
#include "geometry/primitives.h"
#include "test_common.h"

#include <catch2/catch.hpp>
#include <fstream>

using namespace facesketch;

namespace {

std::vector<Candidate> cloudOf(GpuCurvature& curvature, const Mesh& first)
{
    GpuCandidates gpu(test::device(), curvature, {});
    ContourParams params;
    params.silhouetteThreshold = defaultSilhouetteThreshold(first.V.rows());
    params.suggestiveThreshold = 0.005;
    params.featureSize = meanEdgeLength(first);
    return gpu.build(frameMesh(first, { 30, 20 }, 320, 240, Projection::Perspective), params);
}

bool same(const std::vector<Candidate>& a, const std::vector<Candidate>& b)
{
    if (a.size() != b.size())
        return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].mesh != b[i].mesh || a[i].vertex != b[i].vertex || a[i].types != b[i].types || a[i].screen[0] != b[i].screen[0])
            return false;
    return true;
}

} // namespace

TEST_CASE("curvature_cache: the second run reads the file and gives the same cloud, bad files are recomputed")
{
    test::TempDir dir;
    std::vector<Mesh> meshes;
    for (int m = 0; m < 3; ++m) {
        Mesh t = makeTorus(30.0, 9.0 + m, 64, 32);
        for (Eigen::Index v = 0; v < t.V.rows(); ++v)
            t.V(v, 2) *= 1.0 + 0.1 * std::sin(0.2 * t.V(v, 0) + m);
        meshes.push_back(t);
    }
    const std::vector<float> positions = meshMajorPositions(meshes);
    const Triangles& F = meshes[0].F;
    const Eigen::Index nv = meshes[0].V.rows();

    GpuCurvature computed(test::device(), F, nv);
    computed.setPositions(positions);
    const CachedCurvature first = runCurvatureCached(computed, F, positions, dir / "cache");
    REQUIRE_FALSE(first.restored);
    REQUIRE(first.note.empty());
    REQUIRE(std::filesystem::is_regular_file(first.file));
    CHECK(std::filesystem::file_size(first.file) == 8 + 4 + 24 + 20 * 3 * static_cast<std::uintmax_t>(nv) + 8);
    const std::vector<Candidate> reference = cloudOf(computed, meshes[0]);
    REQUIRE(reference.size() > 50);

    GpuCurvature restored(test::device(), F, nv);
    restored.setPositions(positions);
    const CachedCurvature second = runCurvatureCached(restored, F, positions, dir / "cache");
    CHECK(second.restored);
    CHECK(second.file == first.file);
    CHECK(same(cloudOf(restored, meshes[0]), reference));
    REQUIRE_THROWS_WITH(restored.download(), Catch::Contains("only the packed shapes"));
    restored.run();
    CHECK(restored.download().normal.size() == 3 * 3 * static_cast<size_t>(nv));

    // Other faces: another key, another file.
    std::vector<float> moved = positions;
    moved[0] += 0.5f;
    CHECK(curvatureCacheKey(F, moved) != curvatureCacheKey(F, positions));

    // A flipped byte in the payload, then a truncated file: recomputed, noted, replaced.
    for (const char* damage : { "flip", "truncate" }) {
        INFO(damage);
        {
            std::fstream f(first.file, std::ios::in | std::ios::out | std::ios::binary);
            if (std::string(damage) == "flip") {
                f.seekp(100);
                f.put('\x5a');
            }
        }
        if (std::string(damage) == "truncate")
            std::filesystem::resize_file(first.file, 1000);
        GpuCurvature again(test::device(), F, nv);
        again.setPositions(positions);
        const CachedCurvature third = runCurvatureCached(again, F, positions, dir / "cache");
        CHECK_FALSE(third.restored);
        CHECK_THAT(third.note, Catch::Contains(std::string(damage) == "flip" ? "checksum" : "truncated"));
        CHECK(same(cloudOf(again, meshes[0]), reference));
        GpuCurvature fixed(test::device(), F, nv);
        fixed.setPositions(positions);
        CHECK(runCurvatureCached(fixed, F, positions, dir / "cache").restored);
    }

    // No folder: no file, just the pass.
    GpuCurvature plain(test::device(), F, nv);
    plain.setPositions(positions);
    const CachedCurvature none = runCurvatureCached(plain, F, positions, {});
    CHECK_FALSE(none.restored);
    CHECK(none.file.empty());
    REQUIRE_NO_VALIDATION_MESSAGES();
}

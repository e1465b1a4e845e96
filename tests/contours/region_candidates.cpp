#include "contours/region_candidates.h"
#include "contours/candidates.h"
#include "core/error.h"
#include "tori.h"

#include <catch2/catch.hpp>

using namespace facesketch;

namespace {

void requireSame(const std::vector<Candidate>& got, const std::vector<Candidate>& want)
{
    REQUIRE(got.size() == want.size());
    for (size_t i = 0; i < got.size(); ++i) {
        INFO("candidate " << i << ": vertex " << want[i].vertex);
        REQUIRE(got[i].mesh == want[i].mesh);
        REQUIRE(got[i].vertex == want[i].vertex);
        REQUIRE(got[i].types == want[i].types);
        for (int k = 0; k < 3; ++k)
            REQUIRE(got[i].world[k] == want[i].world[k]);
        for (int k = 0; k < 2; ++k)
            REQUIRE(got[i].screen[k] == want[i].screen[k]);
        REQUIRE(got[i].depth == want[i].depth);
    }
}

} // namespace

TEST_CASE("region_candidates: a box's candidates from the region's curvature equal the whole mesh's, bit for bit, both filters")
{
    const Mesh torus = test::bumpyTori().front();
    const Eigen::Index nv = torus.V.rows();
    std::vector<std::uint32_t> flags(nv, 0);
    for (Eigen::Index v = 0; v < nv; v += 53)
        flags[v] = VertexLabelled;
    for (Eigen::Index v = 20; v < nv; v += 171)
        flags[v] = VertexExcluded;
    RegionCandidates region(torus.F, nv, flags);
    const Curvature whole = estimateCurvature(torus);
    ContourParams p;
    p.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    p.suggestiveThreshold = 0.005;
    p.featureSize = meanEdgeLength(torus);
    const Camera camera = frameMesh(torus, { 30, 25 }, 640, 480, Projection::Perspective);

    for (const SuggestiveFilter filter : { SuggestiveFilter::VertexStrength, SuggestiveFilter::RtscCrossing }) {
        p.suggestiveFilter = filter;
        p.rtscThreshold = 0.002;
        // A box round the middle suggestive candidate of the whole view.
        p.rect[0] = p.rect[1] = -1e30;
        p.rect[2] = p.rect[3] = 1e30;
        std::vector<Candidate> seen;
        for (const Candidate& c : contourCandidates({ torus }, { whole }, flags, camera, p))
            if (c.types & ContourSuggestive)
                seen.push_back(c);
        REQUIRE(!seen.empty());
        const Candidate& middle = seen[seen.size() / 2];
        p.rect[0] = middle.screen[0] - 90;
        p.rect[1] = middle.screen[1] - 70;
        p.rect[2] = middle.screen[0] + 90;
        p.rect[3] = middle.screen[1] + 70;
        const std::vector<Candidate> want = contourCandidates({ torus }, { whole }, flags, camera, p);
        size_t suggestive = 0;
        for (const Candidate& c : want)
            suggestive += (c.types & ContourSuggestive) != 0;
        INFO((filter == SuggestiveFilter::RtscCrossing ? "rtsc" : "vertex strength")
            << ": " << want.size() << " candidates, " << suggestive << " suggestive");
        REQUIRE(suggestive > 5);
        requireSame(region.build(torus, camera, p), want);
        // The region is a part of the mesh, not all of it.
        REQUIRE(region.lastRegionVertices() < nv / 2);
        REQUIRE(region.lastRegionVertices() > 0);

        // A sphere culls too; a box off screen has no region and no candidates.
        p.sphere[0] = torus.V(0, 0);
        p.sphere[1] = torus.V(0, 1);
        p.sphere[2] = torus.V(0, 2);
        p.sphere[3] = 25;
        requireSame(region.build(torus, camera, p), contourCandidates({ torus }, { whole }, flags, camera, p));
        p.sphere[3] = 1e30;
        p.rect[0] = p.rect[2] = 5000;
        REQUIRE(region.build(torus, camera, p).empty());
        REQUIRE(region.lastRegionVertices() == 0);
    }

    // Whole view: the region is the whole mesh.
    ContourParams all;
    all.silhouetteThreshold = p.silhouetteThreshold;
    all.featureSize = p.featureSize;
    requireSame(region.build(torus, camera, all), contourCandidates({ torus }, { whole }, flags, camera, all));

    Mesh other = torus;
    other.V.conservativeResize(nv - 1, 3);
    REQUIRE_THROWS_AS(region.build(other, camera, all), Error);
    REQUIRE_THROWS_AS(RegionCandidates(torus.F, nv, std::vector<std::uint32_t>(3, 0)), Error);
}

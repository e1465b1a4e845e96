#include "contours/candidates.h"
#include "core/error.h"
#include "geometry/primitives.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;

namespace {

// A Gaussian bump h(r) = A exp(-r^2 / 2 s^2) on a square grid: seen from straight above, its
// radial curvature changes sign at the inflection circle r = s and grows towards the top, so
// that circle is its suggestive contour (DeCarlo et al. 2003, figure 3).
Mesh bump(double A, double s, int n, double size)
{
    Mesh m = makeGrid(n, n, size, size);
    for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
        const double r2 = m.V(v, 0) * m.V(v, 0) + m.V(v, 1) * m.V(v, 1);
        m.V(v, 2) = A * std::exp(-r2 / (2 * s * s));
    }
    return m;
}

// A camera looking down -z at the xy plane (azimuth 0 looks along -z in our convention).
Camera topCamera(int size = 512)
{
    return frameSphere({ 0, 0, 0 }, 45.0, { 0, 0 }, size, size);
}

// The candidates are all suggestive, within one grid spacing of the inflection circle r = s
// (the zero of the height field graph's h''), and close round it: every octant has some.
void requireInflectionRing(const std::vector<Candidate>& cands, double s)
{
    REQUIRE(cands.size() > 40);
    int octants[8] = {};
    for (const Candidate& cand : cands) {
        REQUIRE(cand.types == ContourSuggestive);
        const double r = std::hypot(cand.world[0], cand.world[1]);
        INFO("candidate at r = " << r);
        REQUIRE(std::abs(r - s) < 0.5 + 1e-9);
        ++octants[static_cast<int>(std::floor((std::atan2(cand.world[1], cand.world[0]) + M_PI) / (M_PI / 4))) % 8];
    }
    for (int o = 0; o < 8; ++o)
        REQUIRE(octants[o] > 0);
}

} // namespace

TEST_CASE("candidates: the silhouette of a sphere is the band |n.v| < threshold")
{
    const Mesh sphere = makeIcosphere(10.0, 4);
    const Curvature c = estimateCurvature(sphere);
    ContourParams p;
    p.silhouetteThreshold = defaultSilhouetteThreshold(sphere.V.rows());
    p.suggestiveThreshold = 1e30; // silhouettes only
    p.featureSize = meanEdgeLength(sphere);
    const Camera camera = frameSphere({ 0, 0, 0 }, 10.0, { 0, 0 }, 256, 256);
    const std::vector<Candidate> cands = contourCandidates({ sphere }, { c }, {}, camera, p);
    long expected = 0;
    for (Eigen::Index v = 0; v < sphere.V.rows(); ++v)
        expected += std::abs(sphere.V(v, 2) / 10.0) < p.silhouetteThreshold;
    REQUIRE(static_cast<long>(cands.size()) == expected);
    for (const Candidate& cand : cands) {
        REQUIRE(cand.types == ContourSilhouette);
        REQUIRE(std::abs(cand.world[2] / 10.0) < p.silhouetteThreshold);
        // On screen, the silhouette is the sphere's outline.
        const double r = std::hypot(cand.screen[0] - 128.0, cand.screen[1] - 128.0);
        REQUIRE(r == Approx(128.0 / 1.05).epsilon(0.01));
    }
}

TEST_CASE("candidates: the suggestive contour of a bump seen from above is its inflection circle")
{
    const double s = 8.0;
    const Mesh m = bump(10.0, s, 121, 60.0);
    const Curvature c = estimateCurvature(m);
    ContourParams p;
    p.silhouetteThreshold = 0.0;
    p.suggestiveThreshold = 1e-3;
    p.featureSize = meanEdgeLength(m);
    requireInflectionRing(contourCandidates({ m }, { c }, {}, topCamera(), p), s);
}

TEST_CASE("candidates: rtsc's filter finds the bump's inflection circle too, and a higher threshold thins it to nothing")
{
    const double s = 8.0;
    const Mesh m = bump(10.0, s, 121, 60.0);
    const Curvature c = estimateCurvature(m);
    ContourParams p;
    p.silhouetteThreshold = 0.0;
    p.suggestiveFilter = SuggestiveFilter::RtscCrossing;
    p.rtscThreshold = 1e-3;
    p.featureSize = meanEdgeLength(m);
    requireInflectionRing(contourCandidates({ m }, { c }, {}, topCamera(), p), s);
    // The ring's tan(theta) D_w k_r l^2 is bounded: a threshold far above it keeps nothing, and
    // the vertex-strength threshold no longer matters.
    p.rtscThreshold = 1e3;
    p.suggestiveThreshold = 0;
    REQUIRE(contourCandidates({ m }, { c }, {}, topCamera(), p).empty());
    p.rtscThreshold = -1;
    REQUIRE_THROWS_WITH(contourCandidates({ m }, { c }, {}, topCamera(), p), Catch::Contains("rtsc threshold -1"));
}

TEST_CASE("candidates: from below, the bump shows no suggestive contour (it is back-facing)")
{
    const Mesh m = bump(10.0, 8.0, 61, 60.0);
    const Curvature c = estimateCurvature(m);
    ContourParams p;
    p.silhouetteThreshold = 0.0;
    p.suggestiveThreshold = 1e-3;
    p.featureSize = meanEdgeLength(m);
    const Camera below = frameSphere({ 0, 0, 0 }, 45.0, { 180, 0 }, 256, 256);
    REQUIRE(contourCandidates({ m }, { c }, {}, below, p).empty());
}

TEST_CASE("candidates: labelled and excluded vertices, and culling by rectangle and sphere")
{
    const Mesh sphere = makeIcosphere(10.0, 3);
    const Curvature c = estimateCurvature(sphere);
    std::vector<std::uint32_t> flags(sphere.V.rows(), 0);
    Eigen::Index front = 0, back = 0;
    for (Eigen::Index v = 0; v < sphere.V.rows(); ++v) {
        if (sphere.V(v, 2) > sphere.V(front, 2))
            front = v;
        if (sphere.V(v, 2) < sphere.V(back, 2))
            back = v;
    }
    flags[front] = VertexLabelled;
    flags[back] = VertexLabelled;
    ContourParams p;
    p.silhouetteThreshold = 0.1;
    p.suggestiveThreshold = 1e30;
    p.featureSize = 1;
    const Camera camera = frameSphere({ 0, 0, 0 }, 10.0, { 0, 0 }, 256, 256);
    std::vector<Candidate> cands = contourCandidates({ sphere }, { c }, flags, camera, p);
    auto has = [&](Eigen::Index v) { return std::any_of(cands.begin(), cands.end(), [&](const Candidate& x) { return x.vertex == v; }); };
    REQUIRE(has(front)); // labelled and facing the camera
    REQUIRE(!has(back)); // labelled but facing away
    const size_t all = cands.size();

    flags[cands[0].vertex] |= VertexExcluded;
    cands = contourCandidates({ sphere }, { c }, flags, camera, p);
    REQUIRE(cands.size() == all - 1);

    p.rect[0] = 0;
    p.rect[1] = 0;
    p.rect[2] = 128;
    p.rect[3] = 256; // the left half of the image
    cands = contourCandidates({ sphere }, { c }, flags, camera, p);
    REQUIRE(!cands.empty());
    for (const Candidate& x : cands)
        REQUIRE(x.screen[0] <= 128);
    p.sphere[0] = -10;
    p.sphere[3] = 5; // near the leftmost point of the sphere
    for (const Candidate& x : contourCandidates({ sphere }, { c }, flags, camera, p))
        REQUIRE(std::hypot(x.world[0] + 10, x.world[1], x.world[2]) <= 5);
}

TEST_CASE("candidates: the default silhouette threshold follows the thesis at 863 vertices")
{
    REQUIRE(defaultSilhouetteThreshold(863) == Approx(0.14));
    REQUIRE(defaultSilhouetteThreshold(6000) == Approx(0.14 * std::sqrt(863.0 / 6000)));
    REQUIRE_THROWS_AS(defaultSilhouetteThreshold(0), Error);
}

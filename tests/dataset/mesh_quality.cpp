// Mesh quality checks on small cases with known answers.
#include "dataset/mesh_quality.h"
#include "test_common.h"

using namespace facesketch;
using namespace facesketch::dataset;

namespace {

Mesh twoTriangles(const Eigen::Matrix<double, 6, 3>& points)
{
    Mesh m;
    m.V = points;
    m.F.resize(2, 3);
    m.F << 0, 1, 2, 3, 4, 5;
    return m;
}

} // namespace

TEST_CASE("mesh_quality: crossing, separate and touching-at-a-vertex triangles")
{
    Eigen::Matrix<double, 6, 3> p;
    // A triangle in z = 0 pierced by one standing across it.
    p << 0, 0, 0, 4, 0, 0, 0, 4, 0, /**/ 1, 1, -1, 1, 1, 1, 2, 1, 1;
    REQUIRE(selfIntersections(twoTriangles(p)).size() == 1);
    // Lifted above: no intersection.
    p.bottomRows(3).col(2).array() += 3;
    REQUIRE(selfIntersections(twoTriangles(p)).empty());
    // Sharing a vertex index is never reported.
    Mesh m = twoTriangles(p);
    m.F << 0, 1, 2, 0, 4, 5;
    REQUIRE(selfIntersections(m).empty());
    REQUIRE(trianglesIntersect({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0.2, 0.2, -1 }, { 0.2, 0.2, 1 }, { 0.3, 0.2, 1 }));
    REQUIRE(!trianglesIntersect({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 2, 2, -1 }, { 2, 2, 1 }, { 3, 2, 1 }));
}

TEST_CASE("mesh_quality: degenerate, flipped, inward-facing and folded triangles")
{
    Mesh m;
    m.V.resize(5, 3);
    m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 1e-9;
    m.F.resize(3, 3);
    m.F << 0, 1, 2, 0, 2, 3, 0, 1, 4; // the third is a sliver along the x axis
    REQUIRE(degenerateTriangles(m) == std::vector<int> { 2 });
    Vertices mirrored = m.V;
    mirrored.col(0) *= -1; // mirroring reverses every triangle
    REQUIRE(flippedTriangles({ mirrored, m.F }, m.V).size() == 3);
    REQUIRE(flippedTriangles(m, m.V).empty());
    // Counter-clockwise seen from +z: facing away from a centre below the plane.
    REQUIRE(trianglesFacingCentre(m, { 0.5, 0.5, -1 }, { 0, 1 }).empty());
    REQUIRE(trianglesFacingCentre(m, { 0.5, 0.5, 1 }, { 0, 1 }) == std::vector<int> { 0, 1 });
    // Folding the second triangle back over the first makes a 180-degree crease.
    Mesh fold = m;
    fold.F.conservativeResize(2, 3);
    fold.V.row(3) << 0.8, 0.2, 0; // on the first triangle's side of the shared edge 0-2
    REQUIRE(foldedEdges(fold).size() == 1);
    REQUIRE(foldedEdges(m).empty());
}

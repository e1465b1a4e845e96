#include "contours/contour_lines.h"
#include "core/error.h"
#include "geometry/primitives.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace facesketch;

TEST_CASE("contour_lines: a sphere's silhouette from the front is its equator circle")
{
    const Mesh sphere = makeIcosphere(10.0, 4);
    const Curvature c = estimateCurvature(sphere);
    ContourParams p;
    p.suggestiveThreshold = 1e30;
    const ContourLines lines = contourLines(sphere, c, frameSphere({ 0, 0, 0 }, 10, { 0, 0 }, 256, 256), p);
    REQUIRE(lines.silhouette.size() >= 2 * 100);
    REQUIRE(lines.suggestive.empty());
    double length = 0;
    for (size_t i = 0; i < lines.silhouette.size(); i += 2) {
        for (const glm::vec3& q : { lines.silhouette[i], lines.silhouette[i + 1] }) {
            REQUIRE(std::abs(q.z) < 0.05);
            REQUIRE(std::hypot(q.x, q.y) == Approx(10.0).epsilon(0.01));
        }
        length += glm::length(lines.silhouette[i + 1] - lines.silhouette[i]);
    }
    REQUIRE(length == Approx(2 * M_PI * 10).epsilon(0.02)); // one closed loop, no doubled segments
}

TEST_CASE("contour_lines: the suggestive line of a bump from above is its inflection circle")
{
    Mesh m = makeGrid(121, 121, 60, 60);
    for (Eigen::Index v = 0; v < m.V.rows(); ++v)
        m.V(v, 2) = 10 * std::exp(-(m.V(v, 0) * m.V(v, 0) + m.V(v, 1) * m.V(v, 1)) / (2 * 64.0));
    const Curvature c = estimateCurvature(m);
    ContourParams p;
    p.suggestiveThreshold = 1e-3;
    p.featureSize = meanEdgeLength(m);
    const ContourLines lines = contourLines(m, c, frameSphere({ 0, 0, 0 }, 45, { 0, 0 }, 256, 256), p);
    REQUIRE(lines.suggestive.size() > 40);
    double length = 0;
    for (size_t i = 0; i < lines.suggestive.size(); i += 2) {
        for (const glm::vec3& q : { lines.suggestive[i], lines.suggestive[i + 1] })
            REQUIRE(std::abs(std::hypot(q.x, q.y) - 8.0) < 0.1);
        length += glm::length(lines.suggestive[i + 1] - lines.suggestive[i]);
    }
    REQUIRE(length == Approx(2 * M_PI * 8).epsilon(0.03));
}

TEST_CASE("contour_lines: rtsc's filter keeps the passing part of a segment, the vertex-strength filter drops it whole")
{
    // One triangle A, B, C with a hand-made curvature: normals +z, dir1 along x, and a view in
    // the x-z plane, so that k_r = k1 and tan(theta) D_w k_r = tan(theta) C111 (no torsion).
    // k_r crosses zero at the middle of AB and of AC; C111 there is 0.5 and -1.5, so the test
    // passes on the first quarter of the segment from AB's crossing towards AC's.
    Mesh m;
    m.V = Vertices(3, 3);
    m.V << 0, 0, 0, 10, 0, 0, 0, 10, 0;
    m.F = Triangles(1, 3);
    m.F << 0, 1, 2;
    Curvature c;
    c.normal = Vertices(3, 3);
    c.dir1 = Vertices(3, 3);
    c.dir2 = Vertices(3, 3);
    for (int v = 0; v < 3; ++v) {
        c.normal.row(v) << 0, 0, 1;
        c.dir1.row(v) << 1, 0, 0;
        c.dir2.row(v) << 0, 1, 0;
    }
    c.k1 = Eigen::Vector3d(-1, 1, 1);
    c.k2 = Eigen::Vector3d::Zero();
    c.area = Eigen::Vector3d::Ones();
    c.dcurv = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>::Zero(3, 4);
    c.dcurv.col(0) = Eigen::Vector3d(0, 1, -3);
    const Camera camera = frameSphere({ 5, 5, 0 }, 10, { 40, 0 }, 256, 256);
    for (int v = 0; v < 3; ++v) {
        const glm::dvec3 to = camera.toCamera({ m.V(v, 0), m.V(v, 1), m.V(v, 2) });
        REQUIRE(std::abs(to.y) < 1e-9); // the view lies in the x-z plane, facing the triangle
        REQUIRE(to.z > 0.1);
        REQUIRE(std::abs(to.x) > 0.1);
    }
    ContourParams p;
    p.silhouetteThreshold = 0;
    p.featureSize = 1;
    p.suggestiveThreshold = 0.1;
    REQUIRE(contourLines(m, c, camera, p).suggestive.empty());

    p.suggestiveFilter = SuggestiveFilter::RtscCrossing;
    p.rtscThreshold = 0;
    const ContourLines lines = contourLines(m, c, camera, p);
    REQUIRE(lines.suggestive.size() == 2);
    const glm::vec3 start(5, 0, 0), end = start + 0.25f * (glm::vec3(0, 5, 0) - start);
    for (int k = 0; k < 3; ++k) {
        REQUIRE(lines.suggestive[0][k] == Approx(start[k]).margin(1e-5));
        REQUIRE(lines.suggestive[1][k] == Approx(end[k]).margin(1e-5));
    }
    // A threshold above the segment's best keeps nothing; a negative one is refused.
    p.rtscThreshold = 10;
    REQUIRE(contourLines(m, c, camera, p).suggestive.empty());
    p.rtscThreshold = -1;
    REQUIRE_THROWS_AS(contourLines(m, c, camera, p), Error);
}

TEST_CASE("contour_lines: labelled paths facing the camera, excluded triangles, bad input")
{
    const Mesh sphere = makeIcosphere(10.0, 2);
    const Curvature c = estimateCurvature(sphere);
    ContourParams p;
    const Camera camera = frameSphere({ 0, 0, 0 }, 10, { 0, 0 }, 128, 128);
    Eigen::Index front = 0, back = 0;
    for (Eigen::Index v = 0; v < sphere.V.rows(); ++v) {
        front = sphere.V(v, 2) > sphere.V(front, 2) ? v : front;
        back = sphere.V(v, 2) < sphere.V(back, 2) ? v : back;
    }
    int neighbour = -1; // a vertex next to the front-most one, also facing the camera
    for (Eigen::Index t = 0; t < sphere.F.rows() && neighbour < 0; ++t)
        for (int k = 0; k < 3; ++k)
            if (sphere.F(t, k) == front)
                neighbour = sphere.F(t, (k + 1) % 3);
    std::map<std::string, std::vector<int>> paths = { { "front", { int(front), neighbour } }, { "back", { int(back), int(back) } } };
    ContourLines lines = contourLines(sphere, c, camera, p, {}, paths);
    REQUIRE(lines.labelled.size() == 2); // the back path faces away
    std::vector<std::uint32_t> flags(sphere.V.rows(), VertexExcluded);
    lines = contourLines(sphere, c, camera, p, flags);
    REQUIRE(lines.silhouette.empty());
    paths["bad"] = { 0, 100000 };
    REQUIRE_THROWS_WITH(contourLines(sphere, c, camera, p, {}, paths), Catch::Contains("'bad' has vertex 100000"));
}

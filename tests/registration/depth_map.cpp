// Tests of registration/depth_map: the cylindrical frame, and depth maps of an analytic cylinder
// and sphere (thesis 3.2.12.1).
#include "registration/depth_map.h"

#include "core/error.h"
#include "geometry/primitives.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace facesketch;
using namespace facesketch::registration;

namespace {

// Turns z into y: makeCylinder's axis (z) becomes the frame's vertical axis (y).
Mesh zToY(Mesh mesh)
{
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const Eigen::Vector3d p = mesh.V.row(i);
        mesh.V.row(i) << p.x(), p.z(), -p.y();
    }
    return mesh;
}

} // namespace

TEST_CASE("CylinderFrame: theta 0 ahead, +pi/2 at the face's left, and back again")
{
    CylinderFrame frame;
    frame.origin = { 1, 2, 3 };
    const Eigen::Vector3d ahead = frame.toCylinder({ 1, 7, 13 });
    REQUIRE(ahead.isApprox(Eigen::Vector3d(0, 5, 10)));
    const Eigen::Vector3d left = frame.toCylinder({ 5, 2, 3 });
    REQUIRE(left(0) == Approx(std::numbers::pi / 2));
    REQUIRE(left(2) == Approx(4.0));
    const Eigen::Vector3d p(-7, 11, -2);
    REQUIRE((frame.fromCylinder(frame.toCylinder(p)) - p).norm() < 1e-12);
}

TEST_CASE("frameFromFeaturePoints: up from the mouth to the eyes, right to the face's left, axis at the ears")
{
    const std::vector<std::string> names = { "ex_l", "ex_r", "ch_l", "ch_r", "obs_l", "obs_r" };
    Vertices P(6, 3);
    P << 45, 30, 80, -45, 30, 80, 25, -40, 85, -25, -40, 85, 75, 20, 0, -75, 20, 0;
    const CylinderFrame f = frameFromFeaturePoints(names, P);
    REQUIRE((f.up - Eigen::Vector3d(0, 70, -5).normalized()).norm() < 1e-12);
    REQUIRE(f.right.dot(f.up) == Approx(0.0).margin(1e-12));
    REQUIRE(f.right.x() > 0.99);
    REQUIRE(f.forward.z() > 0.99);
    REQUIRE(f.toCylinder(Eigen::Vector3d(0, 30, 80))(0) == Approx(0.0).margin(1e-12)); // between the eyes: straight ahead
    REQUIRE(f.toCylinder(Eigen::Vector3d(0, 30, 80))(1) == Approx(0.0).margin(1e-9));  // height 0 at the eyes
    REQUIRE_THROWS_WITH(frameFromFeaturePoints({ "ex_l", "ex_r", "ch_l" }, P.topRows(3)), Catch::Contains("'ch_r' is missing"));
}

TEST_CASE("depth map: a cylinder about the axis has its radius everywhere it covers")
{
    const double radius = 40.0;
    const Mesh cylinder = zToY(makeCylinder(radius, 100.0, 48, 10)); // y from 0 to 100
    CylinderFrame frame;
    const Vertices unwrapped = frame.unwrap(cylinder.V);
    DepthGrid grid;
    grid.width = 128;
    grid.height = 64;
    grid.hMin = -10.0;
    grid.hMax = 110.0;
    const DepthMap map = rasterizeDepth(unwrapped, cylinder.F, grid);
    int covered = 0;
    for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x < grid.width; ++x) {
            const double h = grid.centre(x, y)(1);
            const double theta = grid.centre(x, y)(0);
            // The seam triangles (theta near +-pi) are skipped; everything else within h in [0, 100] is covered.
            const bool inside = h > 0.0 && h < 100.0 && std::abs(theta) < std::numbers::pi - 2.0 * std::numbers::pi / 48;
            if (inside) {
                INFO("pixel " << x << ", " << y);
                REQUIRE(map.valid(x, y));
                REQUIRE(map.at(x, y) == Approx(radius).epsilon(1e-12));
                ++covered;
            }
            if (h < 0.0 || h > 100.0)
                REQUIRE_FALSE(map.valid(x, y));
        }
    REQUIRE(covered > 5000);
}

TEST_CASE("depth map: a sphere centred on the axis has depth sqrt(R^2 - h^2)")
{
    const double R = 50.0;
    const Mesh sphere = makeIcosphere(R, 4);
    CylinderFrame frame;
    const Vertices unwrapped = frame.unwrap(sphere.V);
    const DepthGrid grid = gridAround(unwrapped, 256, 256);
    const DepthMap map = rasterizeDepth(unwrapped, sphere.F, grid);
    double worst = 0.0;
    int checked = 0;
    for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x < grid.width; ++x) {
            const Eigen::Vector2d c = grid.centre(x, y);
            if (std::abs(c(1)) > 0.8 * R || std::abs(c(0)) > 3.0)
                continue;
            REQUIRE(map.valid(x, y));
            worst = std::max(worst, std::abs(map.at(x, y) - std::sqrt(R * R - c(1) * c(1))));
            ++checked;
        }
    // The facets of a 4-times subdivided icosphere (edges of about 3.8 mm at R = 50) lie inside
    // the sphere by up to about e^2 / (6 R) = 0.05 mm at their centres (measured worst: 0.060 mm).
    REQUIRE(checked > 30000);
    REQUIRE(worst < 0.07);
    REQUIRE(worst > 0.0);
}

TEST_CASE("sampleBilinear: exact on a linear field, clamped at the edges")
{
    const int W = 7, H = 5;
    std::vector<double> field(W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            field[static_cast<std::size_t>(y * W + x)] = 2.0 * (x + 0.5) - 3.0 * (y + 0.5) + 1.0;
    REQUIRE(sampleBilinear(field, W, H, { 2.3, 3.9 }) == Approx(2.0 * 2.3 - 3.0 * 3.9 + 1.0));
    REQUIRE(sampleBilinear(field, W, H, { 6.5, 0.5 }) == Approx(2.0 * 6.5 - 3.0 * 0.5 + 1.0));
    REQUIRE(sampleBilinear(field, W, H, { -4.0, 0.5 }) == Approx(2.0 * 0.5 - 3.0 * 0.5 + 1.0));
}

// Tests of stats/segmentation: a partition with symmetric groups, sizes after merging, blend
// weights that sum to one, and blending that turns a seam into a ramp.
#include "stats/segmentation.h"

#include "core/error.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>

using namespace facesketch;
using namespace facesketch::stats;

namespace {

// A (2m+1) by (2m+1) grid over [-1, 1]^2 with a bump ("nose") at the centre, symmetric in x.
// Vertex (i, j) is i + (2m + 1) j; the nose tip is the centre vertex.
Mesh bumpGrid(int m)
{
    const int side = 2 * m + 1;
    Mesh mesh;
    mesh.V.resize(side * side, 3);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const double x = (i - m) / double(m), y = (j - m) / double(m);
            mesh.V.row(i + side * j) << x, y, 0.4 * std::exp(-(x * x + y * y) / 0.05);
        }
    mesh.F.resize(2 * (side - 1) * (side - 1), 3);
    int f = 0;
    for (int j = 0; j + 1 < side; ++j)
        for (int i = 0; i + 1 < side; ++i) {
            const int a = i + side * j, b = a + 1, c = a + side, d = c + 1;
            mesh.F.row(f++) << a, b, d;
            mesh.F.row(f++) << a, d, c;
        }
    return mesh;
}

// Largest change of (x_u - x_v) - (truth_u - truth_v) over the mesh edges: the seam.
double largestJump(const Mesh& mesh, const Eigen::VectorXd& face, const Eigen::VectorXd& truth)
{
    double jump = 0.0;
    for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int u = mesh.F(f, c), v = mesh.F(f, (c + 1) % 3);
            const Eigen::Vector3d e
                = (face.segment<3>(3 * u) - face.segment<3>(3 * v)) - (truth.segment<3>(3 * u) - truth.segment<3>(3 * v));
            jump = std::max(jump, e.norm());
        }
    return jump;
}

} // namespace

TEST_CASE("segmentation: groups partition the face, mirror left and right, respect sizes")
{
    const int m = 20, side = 41;
    const Mesh mesh = bumpGrid(m);
    SegmentationOptions options;
    options.clusters = 12;
    options.minVertices = 60;
    options.maxVertices = 600;
    const Segmentation seg = segmentFace(mesh, m + side * m, options);
    REQUIRE(seg.size() >= 2);
    REQUIRE(seg.core.size() == mesh.vertexCount());
    std::vector<int> coreSize(static_cast<size_t>(seg.size()), 0);
    for (Eigen::Index v = 0; v < seg.core.size(); ++v) {
        REQUIRE(seg.core(v) >= 0);
        REQUIRE(seg.core(v) < seg.size());
        ++coreSize[static_cast<size_t>(seg.core(v))];
    }
    for (int g = 0; g < seg.size(); ++g) {
        INFO("group " << g);
        CHECK(coreSize[static_cast<size_t>(g)] >= options.minVertices);
        // Every core vertex is among the group's vertices.
        const std::set<int> members(seg.vertices[static_cast<size_t>(g)].begin(), seg.vertices[static_cast<size_t>(g)].end());
        for (Eigen::Index v = 0; v < seg.core.size(); ++v)
            if (seg.core(v) == g)
                REQUIRE(members.count(static_cast<int>(v)) == 1);
    }
    // Mirror symmetry: vertex (i, j) and (2m - i, j) share a group.
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i)
            REQUIRE(seg.core(i + side * j) == seg.core((2 * m - i) + side * j));
}

TEST_CASE("segmentation: blend weights form a partition of unity")
{
    const Mesh mesh = bumpGrid(15);
    for (int rings : { 0, 1, 3 }) {
        SegmentationOptions options;
        options.clusters = 6;
        options.minVertices = 30;
        options.overlapRings = rings;
        const Segmentation seg = segmentFace(mesh, 15 + 31 * 15, options);
        Eigen::VectorXd total = Eigen::VectorXd::Zero(mesh.vertexCount());
        Eigen::VectorXi holders = Eigen::VectorXi::Zero(mesh.vertexCount());
        for (int g = 0; g < seg.size(); ++g)
            for (size_t i = 0; i < seg.vertices[static_cast<size_t>(g)].size(); ++i) {
                const double w = seg.weights[static_cast<size_t>(g)](static_cast<Eigen::Index>(i));
                REQUIRE(w > 0.0);
                REQUIRE(w <= 1.0);
                total(seg.vertices[static_cast<size_t>(g)][i]) += w;
                ++holders(seg.vertices[static_cast<size_t>(g)][i]);
            }
        INFO("rings " << rings);
        CHECK((total.array() - 1.0).abs().maxCoeff() < 1e-12);
        if (rings == 0)
            CHECK(holders.maxCoeff() == 1);
        else
            CHECK(holders.maxCoeff() >= 2);
    }
}

TEST_CASE("segmentation: overlap turns a seam into a ramp")
{
    const int m = 15;
    const Mesh mesh = bumpGrid(m);
    Eigen::VectorXd truth(3 * mesh.vertexCount());
    for (Eigen::Index v = 0; v < mesh.vertexCount(); ++v)
        truth.segment<3>(3 * v) = mesh.V.row(v).transpose();
    double jump[2] = { 0.0, 0.0 };
    for (int rings : { 0, 3 }) {
        SegmentationOptions options;
        options.clusters = 5;
        options.minVertices = 30;
        options.overlapRings = rings;
        const Segmentation seg = segmentFace(mesh, m + (2 * m + 1) * m, options);
        REQUIRE(seg.size() >= 2);
        // Every group reconstructs the truth plus its own offset of 0, 1, 2, ... mm in z.
        std::vector<Eigen::VectorXd> parts;
        for (int g = 0; g < seg.size(); ++g) {
            const std::vector<Eigen::Index> coords = segmentCoordinates(seg, g);
            Eigen::VectorXd part = truth(coords);
            for (Eigen::Index i = 2; i < part.size(); i += 3)
                part(i) += g;
            parts.push_back(part);
        }
        const Eigen::VectorXd face = blendSegments(seg, parts);
        jump[rings == 0 ? 0 : 1] = largestJump(mesh, face, truth);
        // Offsets of zero blend back to the truth exactly.
        for (int g = 0; g < seg.size(); ++g)
            parts[static_cast<size_t>(g)] = truth(segmentCoordinates(seg, g));
        CHECK((blendSegments(seg, parts) - truth).cwiseAbs().maxCoeff() < 1e-12);
    }
    INFO("largest jump without overlap " << jump[0] << " mm, with 3 rings " << jump[1] << " mm");
    CHECK(jump[0] >= 1.0 - 1e-12);
    // h' peaks at 1.5, spread over 2r = 6 edges: at most 0.25 of the largest offset step.
    CHECK(jump[1] < 0.5 * jump[0]);
}

TEST_CASE("segmentation: rejects a bad nose tip and bad options")
{
    const Mesh mesh = bumpGrid(4);
    REQUIRE_THROWS_AS(segmentFace(mesh, -1), Error);
    REQUIRE_THROWS_AS(segmentFace(mesh, 81), Error);
    SegmentationOptions options;
    options.overlapRings = -1;
    REQUIRE_THROWS_AS(segmentFace(mesh, 40, options), Error);
}

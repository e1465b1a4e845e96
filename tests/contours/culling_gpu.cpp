// Tests of contours/culling_gpu: the bounding spheres, normal cones and sign locks a view of
// the candidate cloud skips work with, against their definitions on a batch of bumpy tori.
#include "contours/culling_gpu.h"

#include "contours/curvature_gpu.h"
#include "geometry/mesh_batch.h"
#include "geometry/wedges.h"
#include "gpu/buffers.h"
#include "test_common.h"
#include "tori.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

using namespace facesketch;
using test::bumpyTori;

TEST_CASE("culling_gpu: each vertex's bounding sphere holds it in every mesh, and touches the farthest")
{
    const std::vector<Mesh> meshes = bumpyTori();
    const Eigen::Index nv = meshes[0].V.rows();
    GpuCurvature gpu(test::device(), meshes[0].F, nv);
    const std::vector<float> positions = meshMajorPositions(meshes);
    gpu.setPositions(positions);
    const GpuCulling culling(test::device(), gpu);
    const std::vector<std::array<double, 4>>& bounds = culling.vertexBounds();
    REQUIRE(bounds.size() == static_cast<size_t>(nv));
    double widest = 0;
    for (Eigen::Index v = 0; v < nv; ++v) {
        const Eigen::Vector3d centre(bounds[v][0], bounds[v][1], bounds[v][2]);
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        double farthest = 0;
        for (size_t m = 0; m < meshes.size(); ++m) {
            const Eigen::Vector3d p = meshInBatch(positions, nv, m).row(v).transpose().cast<double>();
            mean += p / double(meshes.size());
            farthest = std::max(farthest, (p - centre).norm());
        }
        REQUIRE((mean - centre).norm() < 1e-9);                   // the centre is the mean position
        REQUIRE(farthest <= bounds[v][3]);                        // every mesh's vertex inside
        REQUIRE(farthest == Approx(bounds[v][3]).epsilon(1e-12)); // and no larger than needed
        widest = std::max(widest, bounds[v][3]);
    }
    INFO("widest sphere " << widest << " mm");
    REQUIRE(widest > 0);    // the tori differ
    REQUIRE(widest < 10.0); // ... by a few mm only (tube radii 10, 12, 14 mm)
    REQUIRE(culling.rings().offsets.size() == static_cast<size_t>(nv) + 1);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("culling_gpu: each vertex's normal cone holds its packed normal in every mesh")
{
    const std::vector<Mesh> meshes = bumpyTori();
    const Eigen::Index nv = meshes[0].V.rows();
    const std::vector<float> positions = meshMajorPositions(meshes);
    GpuCurvature gpu(test::device(), meshes[0].F, nv);
    gpu.setPositions(positions);
    GpuCulling culling(test::device(), gpu);
    REQUIRE(culling.normalCones().empty()); // nothing known before run()
    gpu.run();
    REQUIRE(culling.update(gpu));
    const GpuCurvature::Result r = gpu.download();
    auto check = [&](const std::vector<std::array<double, 4>>& cones) {
        REQUIRE(cones.size() == static_cast<size_t>(nv));
        double widest = 0, excess = -1;
        for (Eigen::Index v = 0; v < nv; ++v) {
            const Eigen::Vector3d axis(cones[v][0], cones[v][1], cones[v][2]);
            REQUIRE(axis.norm() == Approx(1.0).margin(1e-12));
            widest = std::max(widest, cones[v][3]);
            for (size_t m = 0; m < meshes.size(); ++m) {
                const float* p = &r.packed[12 * (m * nv + v)];
                const Eigen::Vector3d n(p[0], p[1], p[2]);
                excess = std::max(excess, std::atan2(n.cross(axis).norm(), n.dot(axis)) - cones[v][3]);
            }
        }
        INFO("widest cone " << widest << " rad, normals at most " << excess << " rad inside their cone's edge");
        REQUIRE(excess < -1e-5); // every normal inside, with the cone's slack of 1e-4 to spare
        REQUIRE(widest < 0.5);   // three similar tori: narrow cones, so views can use them
    };
    check(culling.normalCones());
    const std::vector<std::array<double, 4>> fromRun = culling.normalCones();
    REQUIRE_FALSE(culling.update(gpu)); // nothing changed since
    REQUIRE(culling.normalCones() == fromRun);
    gpu.setPositions(positions);
    REQUIRE(culling.update(gpu));
    REQUIRE(culling.normalCones().empty()); // stale with new positions
    gpu.uploadShapes(gpu.downloadShapes());
    REQUIRE(culling.update(gpu));
    REQUIRE(culling.normalCones() == fromRun); // restored shapes (the curvature cache) give the same cones
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("culling_gpu: sign locks mark the vertices whose one-ring has k1 and k2 of one sign")
{
    const std::vector<Mesh> meshes = bumpyTori();
    const Eigen::Index nv = meshes[0].V.rows();
    const auto meshCount = meshes.size();
    const std::vector<float> positions = meshMajorPositions(meshes);
    GpuCurvature gpu(test::device(), meshes[0].F, nv);
    gpu.setPositions(positions);
    GpuCulling culling(test::device(), gpu);
    auto lockBits = [&] {
        culling.update(gpu);
        std::vector<std::uint32_t> words((meshCount * nv + 31) / 32);
        gpu::readbackBuffer(test::device(), culling.signLocks(), words.data(), words.size() * 4);
        return words;
    };
    for (const std::uint32_t w : lockBits())
        REQUIRE(w == 0); // nothing locked before run()
    gpu.run();
    const GpuCurvature::Result r = gpu.download();
    const std::vector<std::uint32_t> words = lockBits();
    const Neighbours rings = buildNeighbours(buildWedges(meshes[0].F, nv));
    // The sign of k1 where k1 k2 > 0 (the packed, half-float curvatures the kernels read).
    auto sign = [&](size_t m, std::uint32_t v) {
        const float* p = &r.packed[12 * (m * nv + v)];
        return p[6] * p[7] > 0 ? (p[6] > 0 ? 1 : -1) : 0;
    };
    size_t locked = 0;
    for (size_t m = 0; m < meshCount; ++m)
        for (std::uint32_t v = 0; v < nv; ++v) {
            bool expected = sign(m, v) != 0;
            for (std::uint32_t k = rings.offsets[v]; k < rings.offsets[v + 1]; ++k) {
                const std::uint32_t u = rings.vertices[k];
                const bool plane = r.packed[12 * (m * nv + u)] != 0 || r.packed[12 * (m * nv + u) + 1] != 0
                    || r.packed[12 * (m * nv + u) + 2] != 0; // else never read: no lock broken
                expected = expected && (!plane || sign(m, u) == sign(m, v));
            }
            const size_t i = v * meshCount + m; // batch layout
            const bool got = (words[i / 32] >> (i % 32)) & 1u;
            if (got != expected)
                FAIL("mesh " << m << " vertex " << v << ": lock " << got << ", expected " << expected);
            locked += got;
        }
    // A torus is convex outside and saddle-shaped inside: both kinds occur.
    INFO(locked << " of " << meshCount * nv << " locked");
    REQUIRE(locked > meshCount * nv / 4);
    REQUIRE(locked < meshCount * nv * 3 / 4);
    // New positions clear them; shapes restored from a cache set them again.
    gpu.setPositions(positions);
    for (const std::uint32_t w : lockBits())
        REQUIRE(w == 0);
    gpu.uploadShapes(gpu.downloadShapes());
    REQUIRE(lockBits() == words);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

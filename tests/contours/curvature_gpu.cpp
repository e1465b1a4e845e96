#include "contours/curvature_gpu.h"
#include "contours/curvature.h"
#include "core/error.h"
#include "core/random.h"
#include "geometry/mesh_batch.h"
#include "geometry/primitives.h"
#include "test_common.h"
#include "tori.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

using namespace facesketch;
using test::bumpyTori;

namespace {

Eigen::Matrix3d secondForm(double k1, double k2, const Eigen::Vector3d& d1, const Eigen::Vector3d& d2)
{
    return k1 * d1 * d1.transpose() + k2 * d2 * d2.transpose();
}

} // namespace

TEST_CASE("curvature_gpu: matches the double-precision CPU reference on a batch of meshes")
{
    const std::vector<Mesh> meshes = bumpyTori();
    const Eigen::Index nv = meshes[0].V.rows();
    const std::vector<float> positions = meshMajorPositions(meshes);

    GpuCurvature gpu(test::device(), meshes[0].F, nv);
    gpu.setPositions(positions);
    gpu.run();
    const GpuCurvature::Result r = gpu.download();

    // Float positions of ~40 mm give curvature to about 1e-5 relative; C, a difference of
    // curvatures over ~3 mm edges, to about 1e-2 of its range. Compared: frame-independent
    // quantities (the tensors), so directions at near-umbilic points cannot flip the outcome.
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Curvature c = estimateCurvature(meshes[m]);
        const double kScale = std::max(c.k1.cwiseAbs().maxCoeff(), c.k2.cwiseAbs().maxCoeff());
        const double cScale = c.dcurv.cwiseAbs().maxCoeff();
        double worstN = 0, worstK = 0, worstC = 0, worstArea = 0;
        for (Eigen::Index v = 0; v < nv; ++v) {
            const size_t i = m * nv + v;
            const Eigen::Vector3d n(r.normal[3 * i], r.normal[3 * i + 1], r.normal[3 * i + 2]);
            const Eigen::Vector3d d1(r.direction[3 * i], r.direction[3 * i + 1], r.direction[3 * i + 2]);
            const Eigen::Vector3d d2 = n.cross(d1);
            const double k1 = r.curvature[4 * i], k2 = r.curvature[4 * i + 1], area = r.curvature[4 * i + 2];
            worstN = std::max(worstN, (n - c.normal.row(v).transpose()).norm());
            worstArea = std::max(worstArea, std::abs(area - c.area[v]) / c.area[v]);
            REQUIRE(k1 >= k2);
            const Eigen::Matrix3d gpuII = secondForm(k1, k2, d1, d2);
            const Eigen::Matrix3d cpuII = secondForm(c.k1[v], c.k2[v], c.dir1.row(v).transpose(), c.dir2.row(v).transpose());
            worstK = std::max(worstK, (gpuII - cpuII).cwiseAbs().maxCoeff() / kScale);
            for (double angle : { 0.0, 0.7, 1.9 }) {
                const Eigen::Vector3d x = std::cos(angle) * c.dir1.row(v).transpose() + std::sin(angle) * c.dir2.row(v).transpose();
                auto cubic = [](const float* d, double a, double b) {
                    return d[0] * a * a * a + 3 * d[1] * a * a * b + 3 * d[2] * a * b * b + d[3] * b * b * b;
                };
                const float* gd = &r.derivative[4 * i];
                float cd[4];
                for (int k = 0; k < 4; ++k)
                    cd[k] = static_cast<float>(c.dcurv(v, k));
                const double gpuC = cubic(gd, x.dot(d1), x.dot(d2));
                const double cpuC = cubic(cd, x.dot(c.dir1.row(v)), x.dot(c.dir2.row(v)));
                worstC = std::max(worstC, std::abs(gpuC - cpuC) / cScale);
            }
        }
        INFO("mesh " << m << ": normal " << worstN << ", II " << worstK << " of |k|max " << kScale << ", C(x,x,x) " << worstC
                     << " of |C|max " << cScale << ", area " << worstArea);
        CHECK(worstN < 1e-5);
        CHECK(worstArea < 1e-4);
        CHECK(worstK < 1e-4);
        CHECK(worstC < 1e-2);
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("curvature_gpu: a sphere's curvature is 1/r on the GPU too")
{
    const Mesh sphere = makeIcosphere(20.0, 4);
    std::vector<float> positions;
    for (Eigen::Index v = 0; v < sphere.V.rows(); ++v)
        for (int c = 0; c < 3; ++c)
            positions.push_back(static_cast<float>(sphere.V(v, c)));
    GpuCurvature gpu(test::device(), sphere.F, sphere.V.rows());
    gpu.setPositions(positions);
    gpu.run();
    const GpuCurvature::Result r = gpu.download();
    for (Eigen::Index v = 0; v < sphere.V.rows(); ++v) {
        INFO("vertex " << v);
        REQUIRE(r.curvature[4 * v] == Approx(0.05).epsilon(0.01));
        REQUIRE(r.curvature[4 * v + 1] == Approx(0.05).epsilon(0.01));
    }
    REQUIRE_THROWS_AS(gpu.setPositions(std::vector<float>(7, 0.0f)), Error);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("curvature_gpu: the packed shape decodes to the full-precision values")
{
    const Mesh torus = makeTorus(30.0, 10.0, 64, 32);
    std::vector<float> positions;
    for (Eigen::Index v = 0; v < torus.V.rows(); ++v)
        for (int c = 0; c < 3; ++c)
            positions.push_back(static_cast<float>(torus.V(v, c)));
    GpuCurvature gpu(test::device(), torus.F, torus.V.rows());
    gpu.setPositions(positions);
    gpu.run();
    const GpuCurvature::Result r = gpu.download();
    double worstVector = 0, worstK = 0, worstC = 0;
    for (Eigen::Index v = 0; v < torus.V.rows(); ++v) {
        const float* p = &r.packed[12 * v];
        for (int k = 0; k < 3; ++k) {
            worstVector = std::max(
                { worstVector, double(std::abs(p[k] - r.normal[3 * v + k])), double(std::abs(p[3 + k] - r.direction[3 * v + k])) });
        }
        for (int k = 0; k < 2; ++k)
            worstK = std::max(worstK, double(std::abs(p[6 + k] - r.curvature[4 * v + k]) / std::abs(r.curvature[4 * v + k])));
        for (int k = 0; k < 4; ++k)
            worstC = std::max(worstC, std::abs(p[8 + k] - r.derivative[4 * v + k]) - 1e-3 * std::abs(r.derivative[4 * v + k]));
    }
    INFO("unit vectors " << worstVector << ", curvature relative " << worstK << ", derivative excess " << worstC);
    REQUIRE(worstVector < 1e-4); // octahedral snorm16: about 3e-5
    REQUIRE(worstK < 1e-3);      // half floats: 2^-11 relative
    REQUIRE(worstC < 1e-7);      // half floats, down to their subnormal range
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("curvature_gpu: host decoders of half floats and octahedral vectors")
{
    REQUIRE(halfToFloat(0x3c00) == 1.0f);
    REQUIRE(halfToFloat(0xc000) == -2.0f);
    REQUIRE(halfToFloat(0x7bff) == 65504.0f);
    REQUIRE(halfToFloat(0x0001) == std::ldexp(1.0f, -24));
    REQUIRE(std::isinf(halfToFloat(0x7c00)));
    // (x, y) = (0, 0) is +z; (32767, 0) is +x; (0, -32767) is -y; the corners fold to -z.
    REQUIRE((octDecode(0x00000000) - Eigen::Vector3d(0, 0, 1)).norm() < 1e-9);
    REQUIRE((octDecode(0x00007fff) - Eigen::Vector3d(1, 0, 0)).norm() < 1e-9);
    REQUIRE((octDecode(0x80010000) - Eigen::Vector3d(0, -1, 0)).norm() < 1e-9);
    REQUIRE((octDecode(0x7fff7fff) - Eigen::Vector3d(0, 0, -1)).norm() < 1e-6);
}

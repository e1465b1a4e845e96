#include "geometry/normals.h"

#include "core/error.h"

#include <Eigen/Geometry>
#include <cmath>

namespace facesketch {

Vertices vertexNormals(const Mesh& mesh)
{
    Vertices N = Vertices::Zero(mesh.V.rows(), 3);
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
        const Eigen::RowVector3d a = mesh.V.row(mesh.F(t, 0)), b = mesh.V.row(mesh.F(t, 1)), c = mesh.V.row(mesh.F(t, 2));
        const Eigen::RowVector3d n = (b - a).cross(c - a);
        for (int k = 0; k < 3; ++k)
            N.row(mesh.F(t, k)) += n;
    }
    for (Eigen::Index v = 0; v < N.rows(); ++v) {
        const double len = N.row(v).norm();
        N.row(v) = len > 0 ? Eigen::RowVector3d(N.row(v) / len) : Eigen::RowVector3d::Zero();
    }
    return N;
}

std::vector<float> vertexNormalsBatch(const std::vector<float>& positions, const Triangles& F, Eigen::Index vertexCount)
{
    const size_t stride = static_cast<size_t>(vertexCount) * 3;
    if (stride == 0 || positions.size() % stride != 0)
        fail("vertexNormalsBatch: ", positions.size(), " floats is not a whole number of meshes of ", vertexCount, " vertices");
    std::vector<float> normals(positions.size());
    std::vector<double> sum(stride);
    for (size_t base = 0; base < positions.size(); base += stride) {
        std::fill(sum.begin(), sum.end(), 0.0);
        const float* p = &positions[base];
        for (Eigen::Index t = 0; t < F.rows(); ++t) {
            const float* a = p + 3 * F(t, 0);
            const float* b = p + 3 * F(t, 1);
            const float* c = p + 3 * F(t, 2);
            const double e1[3] = { double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2] };
            const double e2[3] = { double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2] };
            const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
            for (int k = 0; k < 3; ++k)
                for (int j = 0; j < 3; ++j)
                    sum[3 * F(t, k) + j] += n[j];
        }
        for (size_t v = 0; v < stride; v += 3) {
            const double len = std::sqrt(sum[v] * sum[v] + sum[v + 1] * sum[v + 1] + sum[v + 2] * sum[v + 2]);
            for (int j = 0; j < 3; ++j)
                normals[base + v + j] = len > 0 ? static_cast<float>(sum[v + j] / len) : 0.0f;
        }
    }
    return normals;
}

} // namespace facesketch

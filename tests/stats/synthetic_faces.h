#pragma once
// Synthetic faces for the face-model tests: a 21 by 21 grid "face" with a nose bump, two face
// types (small and large nose, +-8 mm) and six smooth global shape modes of 3 mm, plus a 5%
// width variation and 0.2 mm noise per coordinate. Millimetres, x to the face's left, y up.

#include "core/mesh.h"
#include "core/random.h"

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace facesketch::test {

inline constexpr int kHalf = 10; // grid of 21 by 21 vertices
inline constexpr int kSide = 2 * kHalf + 1;
inline constexpr int kNoseTip = kHalf + kSide * kHalf;

inline Triangles gridTriangles()
{
    Triangles F(2 * (kSide - 1) * (kSide - 1), 3);
    int f = 0;
    for (int j = 0; j + 1 < kSide; ++j)
        for (int i = 0; i + 1 < kSide; ++i) {
            const int a = i + kSide * j, b = a + 1, c = a + kSide, d = c + 1;
            F.row(f++) << a, b, d;
            F.row(f++) << a, d, c;
        }
    return F;
}

// n faces, one per row (x0, y0, z0, x1, ...).
inline Eigen::MatrixXd syntheticFaces(Random& random, int n)
{
    Eigen::MatrixXd faces(n, 3 * kSide * kSide);
    for (int f = 0; f < n; ++f) {
        const double nose = (random.uniform() < 0.5 ? -8.0 : 8.0) + random.normal();
        Eigen::VectorXd a(6);
        for (int j = 0; j < 6; ++j)
            a(j) = 3.0 * random.normal();
        const double width = 1.0 + 0.05 * random.normal();
        for (int j = 0; j < kSide; ++j)
            for (int i = 0; i < kSide; ++i) {
                const double u = (i - kHalf) / double(kHalf), w = (j - kHalf) / double(kHalf);
                const double r2 = u * u + w * w;
                const double bump = std::exp(-r2 / 0.05);
                const double z = (30.0 + nose) * bump + a(0) * u + a(1) * w + a(2) * u * u + a(3) * w * w + a(4) * u * w
                    + a(5) * std::cos(std::numbers::pi * std::sqrt(r2) / 1.5);
                const int v = i + kSide * j;
                faces(f, 3 * v + 0) = 60.0 * u * width + 0.2 * random.normal();
                faces(f, 3 * v + 1) = 60.0 * w + 0.2 * random.normal();
                faces(f, 3 * v + 2) = z + 0.2 * random.normal();
            }
    }
    return faces;
}

} // namespace facesketch::test

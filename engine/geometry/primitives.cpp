#include "geometry/primitives.h"

#include "core/error.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace facesketch {

Mesh makeIcosphere(double radius, int subdivisions)
{
    if (!(radius > 0) || subdivisions < 0 || subdivisions > 8)
        fail("makeIcosphere: radius ", radius, " must be positive and subdivisions ", subdivisions, " in [0, 8]");
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Eigen::RowVector3d> v = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t }, { 0, 1, t }, { 0, -1, -t },
        { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 }, { -t, 0, 1 } };
    std::vector<std::array<int, 3>> f = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 },
        { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 },
        { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
    for (auto& p : v)
        p.normalize();
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<int, int>, int> midpoint;
        auto mid = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            if (auto it = midpoint.find(key); it != midpoint.end())
                return it->second;
            v.push_back((v[a] + v[b]).normalized());
            return midpoint[key] = static_cast<int>(v.size()) - 1;
        };
        std::vector<std::array<int, 3>> next;
        next.reserve(f.size() * 4);
        for (const auto& tri : f) {
            const int ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
            next.push_back({ tri[0], ab, ca });
            next.push_back({ tri[1], bc, ab });
            next.push_back({ tri[2], ca, bc });
            next.push_back({ ab, bc, ca });
        }
        f = std::move(next);
    }
    Mesh m;
    m.V.resize(static_cast<Eigen::Index>(v.size()), 3);
    for (size_t i = 0; i < v.size(); ++i)
        m.V.row(static_cast<Eigen::Index>(i)) = v[i] * radius;
    m.F.resize(static_cast<Eigen::Index>(f.size()), 3);
    for (size_t i = 0; i < f.size(); ++i)
        m.F.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
    return m;
}

Mesh makeTorus(double R, double r, int ringSegments, int tubeSegments)
{
    if (!(r > 0) || !(R > r) || ringSegments < 3 || tubeSegments < 3)
        fail("makeTorus: need 0 < r < R and at least 3 segments (got R ", R, ", r ", r, ", ", ringSegments, "x", tubeSegments, ")");
    Mesh m;
    m.V.resize(static_cast<Eigen::Index>(ringSegments) * tubeSegments, 3);
    m.F.resize(2 * static_cast<Eigen::Index>(ringSegments) * tubeSegments, 3);
    Eigen::Index t = 0;
    for (int i = 0; i < ringSegments; ++i)
        for (int j = 0; j < tubeSegments; ++j) {
            const double u = 2 * M_PI * i / ringSegments, v = 2 * M_PI * j / tubeSegments;
            m.V.row(i * tubeSegments + j) << (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v);
            const int a = i * tubeSegments + j, b = ((i + 1) % ringSegments) * tubeSegments + j;
            const int c = ((i + 1) % ringSegments) * tubeSegments + (j + 1) % tubeSegments, d = i * tubeSegments + (j + 1) % tubeSegments;
            m.F.row(t++) << a, b, c;
            m.F.row(t++) << a, c, d;
        }
    return m;
}

Mesh makeCylinder(double radius, double length, int segments, int rings)
{
    if (!(radius > 0) || !(length > 0) || segments < 3 || rings < 1)
        fail("makeCylinder: need a positive size, 3 segments and 1 ring (got ", radius, ", ", length, ", ", segments, ", ", rings, ")");
    Mesh m;
    m.V.resize(static_cast<Eigen::Index>(segments) * (rings + 1), 3);
    m.F.resize(2 * static_cast<Eigen::Index>(segments) * rings, 3);
    for (int k = 0; k <= rings; ++k)
        for (int i = 0; i < segments; ++i) {
            const double a = 2 * M_PI * i / segments;
            m.V.row(k * segments + i) << radius * std::cos(a), radius * std::sin(a), length * k / rings;
        }
    Eigen::Index t = 0;
    for (int k = 0; k < rings; ++k)
        for (int i = 0; i < segments; ++i) {
            const int a = k * segments + i, b = k * segments + (i + 1) % segments, c = b + segments, d = a + segments;
            m.F.row(t++) << a, b, c;
            m.F.row(t++) << a, c, d;
        }
    return m;
}

Mesh makeGrid(int nx, int ny, double width, double height)
{
    if (nx < 2 || ny < 2 || !(width > 0) || !(height > 0))
        fail("makeGrid: need at least 2x2 vertices and a positive size (got ", nx, "x", ny, ", ", width, "x", height, ")");
    Mesh m;
    m.V.resize(static_cast<Eigen::Index>(nx) * ny, 3);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            m.V.row(j * nx + i) << width * (double(i) / (nx - 1) - 0.5), height * (double(j) / (ny - 1) - 0.5), 0.0;
    m.F.resize(2 * static_cast<Eigen::Index>(nx - 1) * (ny - 1), 3);
    Eigen::Index t = 0;
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
            m.F.row(t++) << a, b, d;
            m.F.row(t++) << a, d, c;
        }
    return m;
}

} // namespace facesketch

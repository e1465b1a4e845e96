// Segment-triangle tests follow Moller T, Trumbore B, "Fast, minimum storage ray-triangle
// intersection", Journal of Graphics Tools 2(1), 1997: two triangles in general position
// intersect exactly when an edge of one crosses the other.
#include "dataset/mesh_quality.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace facesketch::dataset {

namespace {

Eigen::Vector3d vertex(const Vertices& V, int i)
{
    return V.row(i).transpose();
}

Eigen::Vector3d normal(const Vertices& V, const Triangles& F, Eigen::Index f)
{
    const Eigen::Vector3d a = vertex(V, F(f, 0)), b = vertex(V, F(f, 1)), c = vertex(V, F(f, 2));
    return (b - a).cross(c - a);
}

} // namespace

bool segmentHitsTriangle(
    const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
    const Eigen::Vector3d dir = q - p, e1 = b - a, e2 = c - a;
    const Eigen::Vector3d h = dir.cross(e2);
    const double det = e1.dot(h);
    const double scale = e1.norm() * e2.norm() * dir.norm();
    if (std::abs(det) <= 1e-12 * scale)
        return false; // parallel or coplanar
    const double inv = 1.0 / det;
    const Eigen::Vector3d s = p - a;
    const double u = inv * s.dot(h);
    if (u < 0 || u > 1)
        return false;
    const Eigen::Vector3d qv = s.cross(e1);
    const double v = inv * dir.dot(qv);
    if (v < 0 || u + v > 1)
        return false;
    const double t = inv * e2.dot(qv);
    return t >= 0 && t <= 1;
}

bool trianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2, const Eigen::Vector3d& b0,
    const Eigen::Vector3d& b1, const Eigen::Vector3d& b2)
{
    return segmentHitsTriangle(a0, a1, b0, b1, b2) || segmentHitsTriangle(a1, a2, b0, b1, b2) || segmentHitsTriangle(a2, a0, b0, b1, b2)
        || segmentHitsTriangle(b0, b1, a0, a1, a2) || segmentHitsTriangle(b1, b2, a0, a1, a2) || segmentHitsTriangle(b2, b0, a0, a1, a2);
}

std::vector<int> degenerateTriangles(const Mesh& mesh, double minArea, double minAngleDeg)
{
    std::vector<int> out;
    const double minSin = std::sin(minAngleDeg * M_PI / 180);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const Eigen::Vector3d p[3] = { vertex(mesh.V, mesh.F(f, 0)), vertex(mesh.V, mesh.F(f, 1)), vertex(mesh.V, mesh.F(f, 2)) };
        const double twiceArea = (p[1] - p[0]).cross(p[2] - p[0]).norm();
        bool bad = twiceArea / 2 < minArea;
        // sin(angle at k) = 2 area / (|e1| |e2|)
        for (int k = 0; k < 3 && !bad; ++k) {
            const double l1 = (p[(k + 1) % 3] - p[k]).norm(), l2 = (p[(k + 2) % 3] - p[k]).norm();
            bad = twiceArea < minSin * l1 * l2;
        }
        if (bad)
            out.push_back(static_cast<int>(f));
    }
    return out;
}

std::vector<int> flippedTriangles(const Mesh& mesh, const Vertices& reference)
{
    std::vector<int> out;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
        if (normal(mesh.V, mesh.F, f).dot(normal(reference, mesh.F, f)) < 0)
            out.push_back(static_cast<int>(f));
    return out;
}

std::vector<int> trianglesFacingCentre(const Mesh& mesh, const Eigen::Vector3d& centre, const std::vector<int>& triangles)
{
    std::vector<int> out;
    for (int f : triangles) {
        const Eigen::Vector3d centroid = (vertex(mesh.V, mesh.F(f, 0)) + vertex(mesh.V, mesh.F(f, 1)) + vertex(mesh.V, mesh.F(f, 2))) / 3;
        if (normal(mesh.V, mesh.F, f).dot(centroid - centre) <= 0)
            out.push_back(f);
    }
    return out;
}

std::vector<std::pair<int, int>> foldedEdges(const Mesh& mesh, double maxAngleDeg)
{
    std::map<std::pair<int, int>, int> firstFace;
    std::vector<std::pair<int, int>> out;
    const double minCos = std::cos(maxAngleDeg * M_PI / 180);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
            const auto key = std::minmax(a, b);
            auto [it, inserted] = firstFace.emplace(key, static_cast<int>(f));
            if (inserted)
                continue;
            const Eigen::Vector3d n1 = normal(mesh.V, mesh.F, it->second).normalized();
            const Eigen::Vector3d n2 = normal(mesh.V, mesh.F, f).normalized();
            if (n1.dot(n2) < minCos)
                out.emplace_back(it->second, static_cast<int>(f));
        }
    return out;
}

std::vector<std::pair<int, int>> selfIntersections(const Mesh& mesh)
{
    const Eigen::Index nf = mesh.F.rows();
    std::vector<std::pair<int, int>> out;
    if (nf == 0)
        return out;
    // Cell size: the mean edge length, so each triangle touches a handful of cells.
    double edgeSum = 0;
    for (Eigen::Index f = 0; f < nf; ++f)
        edgeSum += (vertex(mesh.V, mesh.F(f, 0)) - vertex(mesh.V, mesh.F(f, 1))).norm();
    const double cell = std::max(edgeSum / static_cast<double>(nf), 1e-6);
    const Eigen::Vector3d origin = mesh.V.colwise().minCoeff().transpose();

    std::vector<Eigen::AlignedBox3d> boxes(static_cast<size_t>(nf));
    auto cellOf = [&](const Eigen::Vector3d& x) {
        return Eigen::Vector3i(static_cast<int>(std::floor((x.x() - origin.x()) / cell)),
            static_cast<int>(std::floor((x.y() - origin.y()) / cell)), static_cast<int>(std::floor((x.z() - origin.z()) / cell)));
    };
    auto key = [](const Eigen::Vector3i& c) {
        return (static_cast<std::int64_t>(c.x()) * 73856093) ^ (static_cast<std::int64_t>(c.y()) * 19349663)
            ^ (static_cast<std::int64_t>(c.z()) * 83492791);
    };
    std::unordered_map<std::int64_t, std::vector<int>> grid;
    for (Eigen::Index f = 0; f < nf; ++f) {
        Eigen::AlignedBox3d& box = boxes[static_cast<size_t>(f)];
        for (int k = 0; k < 3; ++k)
            box.extend(vertex(mesh.V, mesh.F(f, k)));
        const Eigen::Vector3i lo = cellOf(box.min()), hi = cellOf(box.max());
        for (int x = lo.x(); x <= hi.x(); ++x)
            for (int y = lo.y(); y <= hi.y(); ++y)
                for (int z = lo.z(); z <= hi.z(); ++z)
                    grid[key({ x, y, z })].push_back(static_cast<int>(f));
    }
    for (Eigen::Index i = 0; i < nf; ++i) {
        const Eigen::AlignedBox3d& bi = boxes[static_cast<size_t>(i)];
        const Eigen::Vector3i lo = cellOf(bi.min()), hi = cellOf(bi.max());
        for (int x = lo.x(); x <= hi.x(); ++x)
            for (int y = lo.y(); y <= hi.y(); ++y)
                for (int z = lo.z(); z <= hi.z(); ++z) {
                    const Eigen::Vector3i here(x, y, z);
                    auto it = grid.find(key(here));
                    if (it == grid.end())
                        continue;
                    for (int j : it->second) {
                        if (j <= i)
                            continue;
                        const Eigen::AlignedBox3d& bj = boxes[static_cast<size_t>(j)];
                        if (!bi.intersects(bj))
                            continue;
                        // Test each pair once: in the cell holding the overlap's min corner.
                        if (cellOf(bi.intersection(bj).min()) != here)
                            continue;
                        bool shared = false;
                        for (int a = 0; a < 3; ++a)
                            for (int b = 0; b < 3; ++b)
                                shared = shared || mesh.F(i, a) == mesh.F(j, b);
                        if (shared)
                            continue;
                        if (trianglesIntersect(vertex(mesh.V, mesh.F(i, 0)), vertex(mesh.V, mesh.F(i, 1)), vertex(mesh.V, mesh.F(i, 2)),
                                vertex(mesh.V, mesh.F(j, 0)), vertex(mesh.V, mesh.F(j, 1)), vertex(mesh.V, mesh.F(j, 2))))
                            out.emplace_back(static_cast<int>(i), j);
                    }
                }
    }
    return out;
}

} // namespace facesketch::dataset

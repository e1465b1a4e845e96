#include "registration/surface_query.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace facesketch::registration {

Eigen::Vector3d closestPointOnTriangle(
    const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Vector3d& bary)
{
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        bary = { 1, 0, 0 };
        return a;
    }
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) {
        bary = { 0, 1, 0 };
        return b;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double v = d1 / (d1 - d3);
        bary = { 1 - v, v, 0 };
        return a + v * ab;
    }
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) {
        bary = { 0, 0, 1 };
        return c;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double w = d2 / (d2 - d6);
        bary = { 1 - w, 0, w };
        return a + w * ac;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        bary = { 0, 1 - w, w };
        return b + w * (c - b);
    }
    const double denom = 1.0 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    bary = { 1 - v - w, v, w };
    return a + ab * v + ac * w;
}

SurfaceQuery::SurfaceQuery(const Mesh& mesh)
    : mesh_(mesh)
{
    const Eigen::Index nf = mesh_.F.rows();
    if (nf == 0 || mesh_.V.rows() == 0)
        fail("SurfaceQuery: the mesh has no triangles");
    lower_ = mesh_.V.colwise().minCoeff().transpose();
    const Eigen::Vector3d upper = mesh_.V.colwise().maxCoeff().transpose();
    const Eigen::Vector3d extent = (upper - lower_).cwiseMax(1e-9);
    // About two triangles per cell on average keeps both the lists and the ring search short.
    double area = 0.0;
    for (Eigen::Index f = 0; f < nf; ++f) {
        const Eigen::Vector3d a = mesh_.V.row(mesh_.F(f, 0)), b = mesh_.V.row(mesh_.F(f, 1)), c = mesh_.V.row(mesh_.F(f, 2));
        area += 0.5 * (b - a).cross(c - a).norm();
    }
    double edge = std::sqrt(2.0 * std::max(area, 1e-18) / static_cast<double>(nf)) * 1.5;
    edge = std::max(edge, extent.maxCoeff() / 256.0);
    for (int k = 0; k < 3; ++k) {
        cells_(k) = std::max(1, std::min(256, static_cast<int>(std::ceil(extent(k) / edge))));
        cellSize_(k) = extent(k) / cells_(k);
    }
    auto cellOf = [&](const Eigen::Vector3d& x) {
        Eigen::Vector3i c;
        for (int k = 0; k < 3; ++k)
            c(k) = std::clamp(static_cast<int>(std::floor((x(k) - lower_(k)) / cellSize_(k))), 0, cells_(k) - 1);
        return c;
    };
    const std::size_t cellCount = static_cast<std::size_t>(cells_.prod());
    std::vector<int> count(cellCount + 1, 0);
    auto forCells = [&](Eigen::Index f, auto&& visit) {
        Eigen::Vector3d lo = mesh_.V.row(mesh_.F(f, 0)), hi = lo;
        for (int i = 1; i < 3; ++i) {
            lo = lo.cwiseMin(mesh_.V.row(mesh_.F(f, i)).transpose());
            hi = hi.cwiseMax(mesh_.V.row(mesh_.F(f, i)).transpose());
        }
        const Eigen::Vector3i c0 = cellOf(lo), c1 = cellOf(hi);
        for (int z = c0(2); z <= c1(2); ++z)
            for (int y = c0(1); y <= c1(1); ++y)
                for (int x = c0(0); x <= c1(0); ++x)
                    visit((static_cast<std::size_t>(z) * cells_(1) + y) * cells_(0) + x);
    };
    for (Eigen::Index f = 0; f < nf; ++f)
        forCells(f, [&](std::size_t cell) { ++count[cell + 1]; });
    for (std::size_t i = 0; i < cellCount; ++i)
        count[i + 1] += count[i];
    cellStart_ = count;
    cellTriangles_.resize(static_cast<std::size_t>(count.back()));
    for (Eigen::Index f = 0; f < nf; ++f)
        forCells(f, [&](std::size_t cell) { cellTriangles_[static_cast<std::size_t>(count[cell]++)] = static_cast<int>(f); });

    std::map<std::pair<int, int>, int> edgeUse;
    for (Eigen::Index f = 0; f < nf; ++f)
        for (int i = 0; i < 3; ++i) {
            const int a = mesh_.F(f, i), b = mesh_.F(f, (i + 1) % 3);
            ++edgeUse[{ std::min(a, b), std::max(a, b) }];
        }
    boundaryEdge_.assign(static_cast<std::size_t>(nf) * 3, 0);
    boundaryVertex_.assign(static_cast<std::size_t>(mesh_.V.rows()), 0);
    for (Eigen::Index f = 0; f < nf; ++f)
        for (int i = 0; i < 3; ++i) {
            const int a = mesh_.F(f, i), b = mesh_.F(f, (i + 1) % 3);
            if (edgeUse[{ std::min(a, b), std::max(a, b) }] == 1) {
                boundaryEdge_[static_cast<std::size_t>(f) * 3 + i] = 1;
                boundaryVertex_[static_cast<std::size_t>(a)] = boundaryVertex_[static_cast<std::size_t>(b)] = 1;
            }
        }
    stamp_.assign(static_cast<std::size_t>(nf), 0);
}

ClosestPoint SurfaceQuery::closest(const Eigen::Vector3d& p) const
{
    if (++query_ == 0) {
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        query_ = 1;
    }
    Eigen::Vector3i c0;
    for (int k = 0; k < 3; ++k)
        // Clamped before the conversion: a far point's cell index may not fit an int.
        c0(k) = static_cast<int>(std::clamp(std::floor((p(k) - lower_(k)) / cellSize_(k)), 0.0, static_cast<double>(cells_(k) - 1)));
    ClosestPoint best;
    best.distance = std::numeric_limits<double>::infinity();
    const double minCell = cellSize_.minCoeff();
    const int maxRing = cells_.maxCoeff();
    for (int ring = 0; ring <= maxRing; ++ring) {
        // Any cell of ring r lies at least (r - 1) cell widths beyond the query's cell.
        if (ring > 0 && best.distance <= (ring - 1) * minCell)
            break;
        for (int z = c0(2) - ring; z <= c0(2) + ring; ++z) {
            if (z < 0 || z >= cells_(2))
                continue;
            for (int y = c0(1) - ring; y <= c0(1) + ring; ++y) {
                if (y < 0 || y >= cells_(1))
                    continue;
                for (int x = c0(0) - ring; x <= c0(0) + ring; ++x) {
                    if (x < 0 || x >= cells_(0))
                        continue;
                    const int chebyshev = std::max({ std::abs(x - c0(0)), std::abs(y - c0(1)), std::abs(z - c0(2)) });
                    if (chebyshev != ring)
                        continue;
                    const std::size_t cell = (static_cast<std::size_t>(z) * cells_(1) + y) * cells_(0) + x;
                    for (int i = cellStart_[cell]; i < cellStart_[cell + 1]; ++i) {
                        const int f = cellTriangles_[static_cast<std::size_t>(i)];
                        if (stamp_[static_cast<std::size_t>(f)] == query_)
                            continue;
                        stamp_[static_cast<std::size_t>(f)] = query_;
                        Eigen::Vector3d bary;
                        const Eigen::Vector3d q = closestPointOnTriangle(p, mesh_.V.row(mesh_.F(f, 0)).transpose(),
                            mesh_.V.row(mesh_.F(f, 1)).transpose(), mesh_.V.row(mesh_.F(f, 2)).transpose(), bary);
                        const double d = (q - p).norm();
                        if (d < best.distance) {
                            best.distance = d;
                            best.point = q;
                            best.triangle = f;
                            best.barycentric = bary;
                        }
                    }
                }
            }
        }
    }
    // On an edge or a corner when a barycentric coordinate vanishes: boundary if that edge (or
    // the corner's vertex) lies on the mesh's boundary.
    const double eps = 1e-9;
    const int f = best.triangle;
    for (int i = 0; i < 3 && !best.onBoundary; ++i) {
        const int opposite = (i + 2) % 3; // edge (i, i+1) is opposite corner i+2
        if (best.barycentric(opposite) <= eps && boundaryEdge_[static_cast<std::size_t>(f) * 3 + i])
            best.onBoundary = true;
        if (best.barycentric(i) >= 1.0 - eps && boundaryVertex_[static_cast<std::size_t>(mesh_.F(f, i))])
            best.onBoundary = true;
    }
    return best;
}

} // namespace facesketch::registration

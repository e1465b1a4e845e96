#pragma once
// A uniform-grid spatial index over 2D points (screen pixels in practice): nearest-point and
// within-radius queries. The stroke mappers (sketch/) look up contour candidates near stroke
// points with it; the grid covers the points' bounding box, so points anywhere (off screen
// too) are indexed, and queries anywhere are answered.
//
// Cost: building O(N + cells); a within-radius query visits the cells the query disc overlaps;
// nearest visits rings of cells outward from the query's cell until no closer point can remain.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace facesketch {

class GridIndex {
public:
    /// Indexes `points` (any number, finite coordinates) in square cells of `cell` units
    /// (> 0). Throws Error for a non-finite point or cell size, naming the point's index.
    GridIndex(const std::vector<Eigen::Vector2d>& points, double cell);

    /// Index of the point nearest q (Euclidean), or -1 if there are none. Ties go to the
    /// lowest index.
    int nearest(const Eigen::Vector2d& q) const;

    /// Indices of the points within `radius` of q (distance <= radius), ascending.
    std::vector<int> withinRadius(const Eigen::Vector2d& q, double radius) const;

    /// Calls f(index, squared distance) for each point within `radius` of q, in no particular
    /// order and without allocating: for callers that rank or filter the points themselves
    /// (sorting thousands of indices per query was most of a stroke's candidate look-up).
    template <typename F> void forEachWithinRadius(const Eigen::Vector2d& q, double radius, F&& f) const;

    /// The k points nearest q within `radius` for which accept(index) holds, as (squared
    /// distance, index) pairs in ascending order (ties: lower index), into `out`. Searches
    /// rings of cells outward from q and stops once no unvisited cell can hold a closer point,
    /// so a query costs about the cells around its k nearest, not the whole disc: with a
    /// small cell, dense clouds (thousands of points in the disc) are cheap.
    template <typename Accept>
    void nearestWithin(
        const Eigen::Vector2d& q, double radius, std::size_t k, Accept&& accept, std::vector<std::pair<double, int>>& out) const;

    std::size_t size() const { return points_.size(); }
    const Eigen::Vector2d& point(int i) const { return points_[static_cast<std::size_t>(i)]; }

private:
    // The cells [xa, xb] x [ya, yb] a query disc overlaps; false when it misses the grid.
    bool cellRange(const Eigen::Vector2d& q, double radius, long& xa, long& xb, long& ya, long& yb) const;
    // Cell coordinate of a value, clamped to the grid (queries far outside stay well-defined).
    long cellX(double x) const;
    long cellY(double y) const;

    std::vector<Eigen::Vector2d> points_;
    double cell_ = 1;
    double x0_ = 0, y0_ = 0;
    long columns_ = 1, rows_ = 1;
    std::vector<int> offsets_; // CSR: points of cell (row r, column c) at [offsets_[r*C+c], offsets_[r*C+c+1])
    std::vector<int> items_;   // point indices, ascending within a cell
};

template <typename F> void GridIndex::forEachWithinRadius(const Eigen::Vector2d& q, double radius, F&& f) const
{
    long xa, xb, ya, yb;
    if (!cellRange(q, radius, xa, xb, ya, yb))
        return;
    const double r2 = radius * radius;
    for (long y = ya; y <= yb; ++y)
        for (long x = xa; x <= xb; ++x) {
            const std::size_t c = static_cast<std::size_t>(y * columns_ + x);
            for (int k = offsets_[c]; k < offsets_[c + 1]; ++k) {
                const int i = items_[static_cast<std::size_t>(k)];
                const double d2 = (points_[static_cast<std::size_t>(i)] - q).squaredNorm();
                if (d2 <= r2)
                    f(i, d2);
            }
        }
}

template <typename Accept>
void GridIndex::nearestWithin(
    const Eigen::Vector2d& q, double radius, std::size_t k, Accept&& accept, std::vector<std::pair<double, int>>& out) const
{
    out.clear();
    if (k == 0 || points_.empty() || !(radius >= 0) || !std::isfinite(q.x()) || !std::isfinite(q.y()))
        return;
    const double r2 = radius * radius;
    // `out` is a max-heap of the best k so far: out.front() is the worst kept.
    auto visit = [&](long x, long y) {
        if (x < 0 || y < 0 || x >= columns_ || y >= rows_)
            return;
        const std::size_t c = static_cast<std::size_t>(y * columns_ + x);
        for (int n = offsets_[c]; n < offsets_[c + 1]; ++n) {
            const int i = items_[static_cast<std::size_t>(n)];
            const std::pair<double, int> candidate((points_[static_cast<std::size_t>(i)] - q).squaredNorm(), i);
            if (candidate.first > r2 || (out.size() == k && !(candidate < out.front())) || !accept(i))
                continue;
            out.push_back(candidate);
            std::push_heap(out.begin(), out.end());
            if (out.size() > k) {
                std::pop_heap(out.begin(), out.end());
                out.pop_back();
            }
        }
    };
    // A cell r rings from q's cell (q's cell clamped to the grid) is at least (r - 1) cells
    // away from q along one axis.
    const long cx = cellX(q.x()), cy = cellY(q.y());
    const long lastRing = std::max(columns_, rows_);
    for (long r = 0; r <= lastRing; ++r) {
        const double bound = r == 0 ? 0.0 : static_cast<double>(r - 1) * cell_;
        if (bound > radius || (out.size() == k && bound * bound > out.front().first))
            break;
        if (r == 0) {
            visit(cx, cy);
            continue;
        }
        for (long x = cx - r; x <= cx + r; ++x) {
            visit(x, cy - r);
            visit(x, cy + r);
        }
        for (long y = cy - r + 1; y <= cy + r - 1; ++y) {
            visit(cx - r, y);
            visit(cx + r, y);
        }
    }
    std::sort_heap(out.begin(), out.end());
}

} // namespace facesketch

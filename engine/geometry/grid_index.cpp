#include "geometry/grid_index.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facesketch {

namespace {
// Grids larger than this many cells per side gain nothing and cost memory: the cell grows.
constexpr long kMaxCellsPerSide = 4096;
} // namespace

GridIndex::GridIndex(const std::vector<Eigen::Vector2d>& points, double cell)
    : points_(points)
    , cell_(cell)
{
    if (!std::isfinite(cell) || !(cell > 0))
        fail("GridIndex: cell size ", cell, " must be positive and finite");
    double x1 = 0, y1 = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Eigen::Vector2d& p = points[i];
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
            fail("GridIndex: point ", i, " is (", p.x(), ", ", p.y(), "), not finite");
        if (i == 0) {
            x0_ = x1 = p.x();
            y0_ = y1 = p.y();
        }
        x0_ = std::min(x0_, p.x());
        y0_ = std::min(y0_, p.y());
        x1 = std::max(x1, p.x());
        y1 = std::max(y1, p.y());
    }
    // Spread-out points (e.g. one far off screen) would make a huge, empty grid: the cell grows
    // until there are at most about four cells per point.
    cell_ = std::max({ cell_, (x1 - x0_) / kMaxCellsPerSide, (y1 - y0_) / kMaxCellsPerSide });
    const double maxCells = 4.0 * static_cast<double>(points.size()) + 16.0;
    for (;;) {
        columns_ = static_cast<long>(std::floor((x1 - x0_) / cell_)) + 1;
        rows_ = static_cast<long>(std::floor((y1 - y0_) / cell_)) + 1;
        if (static_cast<double>(columns_) * static_cast<double>(rows_) <= maxCells)
            break;
        cell_ *= 1.5;
    }
    const std::size_t cells = static_cast<std::size_t>(columns_ * rows_);
    offsets_.assign(cells + 1, 0);
    std::vector<std::size_t> cellOf(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        cellOf[i] = static_cast<std::size_t>(cellY(points[i].y()) * columns_ + cellX(points[i].x()));
        ++offsets_[cellOf[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c)
        offsets_[c + 1] += offsets_[c];
    items_.resize(points.size());
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i)
        items_[static_cast<std::size_t>(fill[cellOf[i]]++)] = static_cast<int>(i);
}

long GridIndex::cellX(double x) const
{
    const double c = std::floor((x - x0_) / cell_);
    return static_cast<long>(std::clamp(c, 0.0, static_cast<double>(columns_ - 1)));
}

long GridIndex::cellY(double y) const
{
    const double c = std::floor((y - y0_) / cell_);
    return static_cast<long>(std::clamp(c, 0.0, static_cast<double>(rows_ - 1)));
}

int GridIndex::nearest(const Eigen::Vector2d& q) const
{
    if (points_.empty())
        return -1;
    const long cx = cellX(q.x()), cy = cellY(q.y());
    int best = -1;
    double bestD2 = std::numeric_limits<double>::infinity();
    const long maxRing = std::max(columns_, rows_);
    for (long ring = 0; ring <= maxRing; ++ring) {
        // Every point in this ring or beyond is at least (ring - 1) cells from q (a query
        // outside the grid starts at the clamped border cell, which keeps this a lower bound).
        if (best >= 0 && static_cast<double>(ring - 1) * cell_ > std::sqrt(bestD2))
            break;
        for (long y = cy - ring; y <= cy + ring; ++y) {
            if (y < 0 || y >= rows_)
                continue;
            const bool edgeRow = y == cy - ring || y == cy + ring;
            for (long x = cx - ring; x <= cx + ring; x += (edgeRow || ring == 0) ? 1 : 2 * ring) {
                if (x < 0 || x >= columns_)
                    continue;
                const std::size_t c = static_cast<std::size_t>(y * columns_ + x);
                for (int k = offsets_[c]; k < offsets_[c + 1]; ++k) {
                    const int i = items_[static_cast<std::size_t>(k)];
                    const double d2 = (points_[static_cast<std::size_t>(i)] - q).squaredNorm();
                    if (d2 < bestD2 || (d2 == bestD2 && i < best)) {
                        bestD2 = d2;
                        best = i;
                    }
                }
            }
        }
    }
    return best;
}

bool GridIndex::cellRange(const Eigen::Vector2d& q, double radius, long& xa, long& xb, long& ya, long& yb) const
{
    if (points_.empty() || !(radius >= 0) || !std::isfinite(q.x()) || !std::isfinite(q.y()))
        return false;
    // Entirely outside the grid's box by more than the radius: nothing.
    if (q.x() + radius < x0_ || q.x() - radius > x0_ + columns_ * cell_ || q.y() + radius < y0_ || q.y() - radius > y0_ + rows_ * cell_)
        return false;
    xa = cellX(q.x() - radius);
    xb = cellX(q.x() + radius);
    ya = cellY(q.y() - radius);
    yb = cellY(q.y() + radius);
    return true;
}

std::vector<int> GridIndex::withinRadius(const Eigen::Vector2d& q, double radius) const
{
    std::vector<int> out;
    forEachWithinRadius(q, radius, [&](int i, double) { out.push_back(i); });
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace facesketch

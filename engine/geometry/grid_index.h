#pragma once
// A uniform-grid spatial index over 2D points (screen pixels in practice): nearest-point and
// within-radius queries. The stroke mappers (sketch/) look up contour candidates near stroke
// points with it; the grid covers the points' bounding box, so points anywhere (off screen
// too) are indexed, and queries anywhere are answered.
//
// Cost: building O(N + cells); a within-radius query visits the cells the query disc overlaps;
// nearest visits rings of cells outward from the query's cell until no closer point can remain.

#include <Eigen/Core>
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

    std::size_t size() const { return points_.size(); }
    const Eigen::Vector2d& point(int i) const { return points_[static_cast<std::size_t>(i)]; }

private:
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

} // namespace facesketch

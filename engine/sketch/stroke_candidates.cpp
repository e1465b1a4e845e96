#include "sketch/stroke_candidates.h"

#include "geometry/grid_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facesketch::sketch {

double pixelsPerMm(const Camera& camera, const Eigen::Vector3d& at)
{
    const Eigen::Matrix<double, 2, 3> P = viewPlaneRows(camera);
    const glm::dvec3 a(at.x(), at.y(), at.z());
    const glm::dvec3 b = a + glm::dvec3(P(1, 0), P(1, 1), P(1, 2));
    const glm::dvec3 pa = camera.project(a), pb = camera.project(b);
    return std::hypot(pb.x - pa.x, pb.y - pa.y);
}

Eigen::Matrix<double, 2, 3> viewPlaneRows(const Camera& camera)
{
    Eigen::Matrix<double, 2, 3> P;
    for (int c = 0; c < 3; ++c) {
        P(0, c) = camera.view[c][0];
        P(1, c) = camera.view[c][1];
    }
    return P;
}

Eigen::Vector3d viewAxis(const Camera& camera)
{
    return { camera.view[0][2], camera.view[1][2], camera.view[2][2] };
}

bool strokeBox(ContourParams& base, const Camera& camera, const std::vector<Eigen::Vector2d>& screen,
    const std::vector<Eigen::Vector3d>& world, double radiusPx, double worldMarginMm)
{
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(x0), hi = -lo;
    bool any = false;
    for (std::size_t i = 0; i < screen.size(); ++i) {
        const Eigen::Vector2d& p = screen[i];
        if (p.x() < -radiusPx || p.y() < -radiusPx || p.x() > camera.width + radiusPx || p.y() > camera.height + radiusPx)
            continue;
        any = true;
        x0 = std::min(x0, p.x());
        y0 = std::min(y0, p.y());
        x1 = std::max(x1, p.x());
        y1 = std::max(y1, p.y());
        lo = lo.cwiseMin(world[i]);
        hi = hi.cwiseMax(world[i]);
    }
    if (!any)
        return false;
    base.rect[0] = x0 - radiusPx;
    base.rect[1] = y0 - radiusPx;
    base.rect[2] = x1 + radiusPx;
    base.rect[3] = y1 + radiusPx;
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    base.sphere[0] = centre.x();
    base.sphere[1] = centre.y();
    base.sphere[2] = centre.z();
    base.sphere[3] = 0.5 * (hi - lo).norm() + worldMarginMm;
    return true;
}

std::vector<std::vector<int>> candidatesPerPoint(const std::vector<Candidate>& cloud, const Camera& camera,
    const std::vector<Eigen::Vector2d>& screen, const std::vector<Eigen::Vector3d>& world, double radiusPx, double depthToleranceMm,
    int maxPerPoint)
{
    std::vector<std::vector<int>> out(screen.size());
    if (cloud.empty())
        return out;
    std::vector<Eigen::Vector2d> at(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
        at[i] = Eigen::Vector2d(cloud[i].screen[0], cloud[i].screen[1]);
    // One-pixel cells (the index grows them when the cloud is sparse): a point's few dozen
    // nearest candidates sit in the cells around it, where a disc of radius 2 tau holds
    // thousands (a face's contours stacked over hundreds of training faces).
    const GridIndex index(at, 1.0);
    const Eigen::Vector3d axis = viewAxis(camera);
    std::vector<double> depth(cloud.size());
    for (std::size_t c = 0; c < cloud.size(); ++c)
        depth[c] = axis.x() * cloud[c].world[0] + axis.y() * cloud[c].world[1] + axis.z() * cloud[c].world[2];
    const std::size_t keep = static_cast<std::size_t>(std::max(maxPerPoint, 0));
    std::vector<std::pair<double, int>> found;
    for (std::size_t i = 0; i < screen.size(); ++i) {
        const double pointDepth = axis.dot(world[i]);
        index.nearestWithin(
            screen[i], radiusPx, keep, [&](int c) { return std::abs(depth[static_cast<std::size_t>(c)] - pointDepth) <= depthToleranceMm; },
            found);
        for (const auto& f : found)
            out[i].push_back(f.second);
    }
    return out;
}

} // namespace facesketch::sketch

#include "sketch/projection.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <limits>

namespace facesketch::sketch {

Eigen::Vector3d unproject(const Camera& camera, double x, double y, double depth)
{
    const glm::dvec4 ndc(2.0 * x / camera.width - 1.0, 1.0 - 2.0 * y / camera.height, depth, 1.0);
    const glm::dvec4 w = glm::inverse(camera.projection * camera.view) * ndc;
    return { w.x / w.w, w.y / w.w, w.z / w.w };
}

namespace {

bool inside(const Eigen::Vector2d& p, const Eigen::Vector4d& limit)
{
    return p.x() >= limit[0] && p.y() >= limit[1] && p.x() <= limit[2] && p.y() <= limit[3];
}

// Ray through pixel (x, y) meets the plane through `centre` with normal `normal`.
Eigen::Vector3d castOnPlane(const Camera& camera, const Eigen::Vector2d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& normal,
    Surface surface, const std::string& viewText)
{
    const Eigen::Vector3d a = unproject(camera, p.x(), p.y(), 0.0), b = unproject(camera, p.x(), p.y(), 1.0);
    const Eigen::Vector3d d = b - a;
    const double denominator = d.dot(normal);
    // A plane within about half a degree of edge-on gives depths that swing wildly with a pixel.
    if (std::abs(denominator) < 1e-2 * d.norm())
        fail("stroke on the ", surfaceName(surface), ": the view (", viewText, ") sees that plane edge-on; choose another surface");
    return a + d * ((centre - a).dot(normal) / denominator);
}

} // namespace

std::vector<Eigen::Vector2d> densify(
    const std::vector<Eigen::Vector2d>& points, double maxGapPx, double tension, const Eigen::Vector4d& limit, std::vector<int>* source)
{
    if (!(maxGapPx > 0) || !std::isfinite(maxGapPx))
        fail("densify: the largest gap ", maxGapPx, " px must be positive");
    std::vector<Eigen::Vector2d> out;
    if (source)
        source->clear();
    const std::size_t n = points.size();
    for (std::size_t i = 0; i < n; ++i) {
        out.push_back(points[i]);
        if (source)
            source->push_back(static_cast<int>(i));
        if (i + 1 == n)
            break;
        const Eigen::Vector2d& p1 = points[i];
        const Eigen::Vector2d& p2 = points[i + 1];
        const double gap = (p2 - p1).norm();
        if (!(gap > maxGapPx) || !inside(p1, limit) || !inside(p2, limit))
            continue;
        // Cardinal spline through p1 and p2, tangents from the neighbours (the ends repeat).
        const Eigen::Vector2d& p0 = i > 0 ? points[i - 1] : p1;
        const Eigen::Vector2d& p3 = i + 2 < n ? points[i + 2] : p2;
        const double s = (1.0 - tension) / 2.0;
        const Eigen::Vector2d m1 = s * (p2 - p0), m2 = s * (p3 - p1);
        auto at = [&](double t) {
            const double t2 = t * t, t3 = t2 * t;
            return Eigen::Vector2d((2 * t3 - 3 * t2 + 1) * p1 + (t3 - 2 * t2 + t) * m1 + (-2 * t3 + 3 * t2) * p2 + (t3 - t2) * m2);
        };
        // The spline's speed varies along t: more pieces until no gap exceeds the threshold
        // (a Hermite segment is at most a few times longer than its chord).
        std::vector<Eigen::Vector2d> piece;
        for (int pieces = static_cast<int>(std::ceil(gap / maxGapPx));; ++pieces) {
            piece.clear();
            double largest = 0;
            Eigen::Vector2d previous = p1;
            for (int k = 1; k <= pieces; ++k) {
                const Eigen::Vector2d q = k == pieces ? p2 : at(static_cast<double>(k) / pieces);
                largest = std::max(largest, (q - previous).norm());
                previous = q;
                if (k < pieces)
                    piece.push_back(q);
            }
            if (largest <= maxGapPx || pieces > 8 * std::ceil(gap / maxGapPx) + 8)
                break;
        }
        for (const Eigen::Vector2d& q : piece) {
            out.push_back(q);
            if (source)
                source->push_back(static_cast<int>(i));
        }
    }
    return out;
}

ProjectedStroke projectStroke(const Stroke& stroke, const Camera& camera, const Mesh& face, double maxGapPx, double tension)
{
    const double w = camera.width, h = camera.height;
    std::vector<Eigen::Vector2d> raw;
    for (const StrokePoint& p : stroke.points)
        raw.emplace_back(p.x, p.y);
    ProjectedStroke out;
    out.screen = densify(raw, maxGapPx, tension, Eigen::Vector4d(-w, -h, 2 * w, 2 * h), &out.source);
    const std::size_t n = out.screen.size();
    out.world.assign(n, Eigen::Vector3d::Zero());
    out.hit.assign(n, 0);

    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    if (face.V.rows() > 0)
        centre = 0.5 * (face.V.colwise().minCoeff() + face.V.colwise().maxCoeff()).transpose();
    const std::string viewText = cat("azimuth ", stroke.view.angles.azimuthDeg, ", elevation ", stroke.view.angles.elevationDeg);
    const glm::dvec3 towards = camera.toCamera(glm::dvec3(centre.x(), centre.y(), centre.z()));
    const Eigen::Vector3d paperNormal(towards.x, towards.y, towards.z);
    auto onPlane = [&](const Eigen::Vector3d& normal, Surface surface) {
        for (std::size_t i = 0; i < n; ++i)
            out.world[i] = castOnPlane(camera, out.screen[i], centre, normal, surface, viewText);
    };
    switch (stroke.surface) {
    case Surface::FrontPlane:
        onPlane(Eigen::Vector3d::UnitZ(), Surface::FrontPlane);
        return out;
    case Surface::ProfilePlane:
        onPlane(Eigen::Vector3d::UnitX(), Surface::ProfilePlane);
        return out;
    case Surface::Paper:
        onPlane(paperNormal, Surface::Paper);
        return out;
    case Surface::Face:
        break;
    }

    // Cast onto the face: the triangles under the stroke's box, bucketed in a screen grid.
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const Eigen::Vector2d& p : out.screen)
        if (inside(p, Eigen::Vector4d(-w, -h, 2 * w, 2 * h))) {
            x0 = std::min(x0, p.x());
            y0 = std::min(y0, p.y());
            x1 = std::max(x1, p.x());
            y1 = std::max(y1, p.y());
        }
    std::vector<double> depth(n, 0.0);
    if (x0 <= x1) {
        const Eigen::Index nv = face.V.rows();
        std::vector<glm::dvec3> screenV(static_cast<std::size_t>(nv));
        for (Eigen::Index v = 0; v < nv; ++v)
            screenV[static_cast<std::size_t>(v)] = camera.project(glm::dvec3(face.V(v, 0), face.V(v, 1), face.V(v, 2)));
        const double cell = 8.0;
        const long columns = static_cast<long>((x1 - x0) / cell) + 1, rows = static_cast<long>((y1 - y0) / cell) + 1;
        std::vector<std::vector<Eigen::Index>> buckets(static_cast<std::size_t>(columns * rows));
        auto clampCell
            = [](double v, long count) { return static_cast<long>(std::clamp(std::floor(v), 0.0, static_cast<double>(count - 1))); };
        for (Eigen::Index t = 0; t < face.F.rows(); ++t) {
            const glm::dvec3 &a = screenV[static_cast<std::size_t>(face.F(t, 0))], &b = screenV[static_cast<std::size_t>(face.F(t, 1))],
                             &c = screenV[static_cast<std::size_t>(face.F(t, 2))];
            const double tx0 = std::min({ a.x, b.x, c.x }), tx1 = std::max({ a.x, b.x, c.x });
            const double ty0 = std::min({ a.y, b.y, c.y }), ty1 = std::max({ a.y, b.y, c.y });
            if (tx1 < x0 || tx0 > x1 || ty1 < y0 || ty0 > y1)
                continue;
            for (long r = clampCell((ty0 - y0) / cell, rows); r <= clampCell((ty1 - y0) / cell, rows); ++r)
                for (long q = clampCell((tx0 - x0) / cell, columns); q <= clampCell((tx1 - x0) / cell, columns); ++q)
                    buckets[static_cast<std::size_t>(r * columns + q)].push_back(t);
        }
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector2d& p = out.screen[i];
            if (p.x() < x0 || p.x() > x1 || p.y() < y0 || p.y() > y1)
                continue;
            double nearest = std::numeric_limits<double>::infinity();
            for (Eigen::Index t : buckets[static_cast<std::size_t>(
                     clampCell((p.y() - y0) / cell, rows) * columns + clampCell((p.x() - x0) / cell, columns))]) {
                const glm::dvec3 &a = screenV[static_cast<std::size_t>(face.F(t, 0))], &b = screenV[static_cast<std::size_t>(face.F(t, 1))],
                                 &c = screenV[static_cast<std::size_t>(face.F(t, 2))];
                // Barycentric coordinates in the screen (either winding: the back of the face
                // counts too; the nearest hit wins).
                const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
                if (area == 0)
                    continue;
                const double u = ((b.x - p.x()) * (c.y - p.y()) - (b.y - p.y()) * (c.x - p.x())) / area;
                const double v = ((c.x - p.x()) * (a.y - p.y()) - (c.y - p.y()) * (a.x - p.x())) / area;
                const double s = 1.0 - u - v;
                if (u < 0 || v < 0 || s < 0)
                    continue;
                const double z = u * a.z + v * b.z + s * c.z;
                if (z < nearest) {
                    nearest = z;
                    depth[i] = z;
                    out.hit[i] = 1;
                }
            }
            out.hits += out.hit[i];
        }
    }
    if (out.hits == 0) {
        out.fellBackToPaper = true;
        onPlane(paperNormal, Surface::Paper);
        return out;
    }
    // Points that missed take the depth interpolated along the stroke between the hits around
    // them (the nearest hit's depth beyond the first and last).
    std::vector<std::size_t> nextHit(n + 1, n);
    for (std::size_t i = n; i-- > 0;)
        nextHit[i] = out.hit[i] ? i : nextHit[i + 1];
    int previous = -1;
    for (std::size_t i = 0; i < n; ++i) {
        if (out.hit[i]) {
            previous = static_cast<int>(i);
            continue;
        }
        const std::size_t next = nextHit[i];
        if (previous < 0)
            depth[i] = depth[next];
        else if (next >= n)
            depth[i] = depth[static_cast<std::size_t>(previous)];
        else {
            const double t = static_cast<double>(i - static_cast<std::size_t>(previous))
                / static_cast<double>(next - static_cast<std::size_t>(previous));
            depth[i] = (1 - t) * depth[static_cast<std::size_t>(previous)] + t * depth[next];
        }
    }
    for (std::size_t i = 0; i < n; ++i)
        out.world[i] = unproject(camera, out.screen[i].x(), out.screen[i].y(), depth[i]);
    return out;
}

} // namespace facesketch::sketch

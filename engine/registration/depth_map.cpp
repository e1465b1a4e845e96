#include "registration/depth_map.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace facesketch::registration {

Eigen::Vector3d CylinderFrame::toCylinder(const Eigen::Vector3d& p) const
{
    const Eigen::Vector3d d = p - origin;
    const double h = up.dot(d);
    const double x = right.dot(d), z = forward.dot(d);
    return { std::atan2(x, z), h, std::hypot(x, z) };
}

Eigen::Vector3d CylinderFrame::fromCylinder(const Eigen::Vector3d& thr) const
{
    return origin + thr(1) * up + thr(2) * (std::sin(thr(0)) * right + std::cos(thr(0)) * forward);
}

Vertices CylinderFrame::unwrap(const Vertices& V) const
{
    Vertices out(V.rows(), 3);
    for (Eigen::Index i = 0; i < V.rows(); ++i)
        out.row(i) = toCylinder(V.row(i).transpose()).transpose();
    return out;
}

CylinderFrame frameFromFeaturePoints(const std::vector<std::string>& names, const Vertices& points)
{
    auto find = [&](const std::string& name, bool required) -> const double* {
        const auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end()) {
            if (required)
                fail("registration frame: feature point '", name, "' is missing");
            return nullptr;
        }
        return points.row(it - names.begin()).data();
    };
    auto get = [&](const std::string& name) { return Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(find(name, true))); };
    const Eigen::Vector3d exL = get("ex_l"), exR = get("ex_r"), chL = get("ch_l"), chR = get("ch_r");
    const Eigen::Vector3d eyes = 0.5 * (exL + exR), mouth = 0.5 * (chL + chR);
    CylinderFrame frame;
    frame.up = eyes - mouth;
    if (!(frame.up.norm() > 0.0))
        fail("registration frame: the eye corners' and mouth corners' midpoints coincide");
    frame.up.normalize();
    frame.right = exL - exR;
    frame.right -= frame.up.dot(frame.right) * frame.up;
    if (!(frame.right.norm() > 1e-9 * (exL - exR).norm()) || !((exL - exR).norm() > 0.0))
        fail("registration frame: ex_l - ex_r is parallel to the face's vertical");
    frame.right.normalize();
    frame.forward = frame.right.cross(frame.up);
    const double* obsL = find("obs_l", false);
    const double* obsR = find("obs_r", false);
    if (obsL && obsR)
        frame.origin = 0.5 * (Eigen::Map<const Eigen::Vector3d>(obsL) + Eigen::Map<const Eigen::Vector3d>(obsR));
    else
        frame.origin = eyes - (exL - exR).norm() * frame.forward;
    // Put the axis's zero height at the eyes so h reads as height above them.
    frame.origin += frame.up.dot(eyes - frame.origin) * frame.up;
    return frame;
}

DepthGrid gridAround(const Vertices& unwrapped, int width, int height, double marginPixels)
{
    if (unwrapped.rows() == 0)
        fail("depth map: no vertices to cover");
    if (width < 2 || height < 2)
        fail("depth map: ", width, " x ", height, " pixels, at least 2 x 2 needed");
    DepthGrid grid;
    grid.width = width;
    grid.height = height;
    const double t0 = unwrapped.col(0).minCoeff(), t1 = unwrapped.col(0).maxCoeff();
    const double h0 = unwrapped.col(1).minCoeff(), h1 = unwrapped.col(1).maxCoeff();
    const double pt = std::max(t1 - t0, 1e-6) * marginPixels / (width - 2.0 * marginPixels);
    const double ph = std::max(h1 - h0, 1e-6) * marginPixels / (height - 2.0 * marginPixels);
    grid.thetaMin = std::max(-std::numbers::pi, t0 - pt);
    grid.thetaMax = std::min(std::numbers::pi, t1 + pt);
    grid.hMin = h0 - ph;
    grid.hMax = h1 + ph;
    return grid;
}

DepthMap rasterizeDepth(const Vertices& unwrapped, const Triangles& F, const DepthGrid& grid)
{
    DepthMap map;
    map.grid = grid;
    const std::size_t pixels = static_cast<std::size_t>(grid.width) * grid.height;
    map.depth.assign(pixels, std::numeric_limits<double>::quiet_NaN());
    map.triangle.assign(pixels, -1);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        Eigen::Vector2d q[3];
        double r[3];
        for (int k = 0; k < 3; ++k) {
            const auto v = unwrapped.row(F(f, k));
            q[k] = grid.toPixel(v(0), v(1));
            r[k] = v(2);
        }
        const double thetaSpan = std::max({ unwrapped(F(f, 0), 0), unwrapped(F(f, 1), 0), unwrapped(F(f, 2), 0) })
            - std::min({ unwrapped(F(f, 0), 0), unwrapped(F(f, 1), 0), unwrapped(F(f, 2), 0) });
        if (thetaSpan > std::numbers::pi)
            continue; // straddles the seam behind the head
        const double area = (q[1] - q[0]).x() * (q[2] - q[0]).y() - (q[1] - q[0]).y() * (q[2] - q[0]).x();
        if (!(std::abs(area) > 1e-14))
            continue; // seen edge-on from the axis: it covers no pixel centre
        const int x0 = std::max(0, static_cast<int>(std::floor(std::min({ q[0].x(), q[1].x(), q[2].x() }) - 0.5)));
        const int x1 = std::min(grid.width - 1, static_cast<int>(std::ceil(std::max({ q[0].x(), q[1].x(), q[2].x() }) - 0.5)));
        const int y0 = std::max(0, static_cast<int>(std::floor(std::min({ q[0].y(), q[1].y(), q[2].y() }) - 0.5)));
        const int y1 = std::min(grid.height - 1, static_cast<int>(std::ceil(std::max({ q[0].y(), q[1].y(), q[2].y() }) - 0.5)));
        const double tolerance = 1e-9;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const Eigen::Vector2d c(x + 0.5, y + 0.5);
                auto edge = [&](int a, int b) { return ((q[b] - q[a]).x() * (c - q[a]).y() - (q[b] - q[a]).y() * (c - q[a]).x()) / area; };
                const double w0 = edge(1, 2), w1 = edge(2, 0), w2 = edge(0, 1);
                if (w0 < -tolerance || w1 < -tolerance || w2 < -tolerance)
                    continue;
                const double depth = w0 * r[0] + w1 * r[1] + w2 * r[2];
                const std::size_t i = static_cast<std::size_t>(y) * grid.width + x;
                // An empty pixel holds NaN; test it first, since an ordered comparison with NaN raises
                // the invalid-operation flag (a trap where floating-point exceptions are on).
                if (std::isnan(map.depth[i]) || depth > map.depth[i]) {
                    map.depth[i] = depth;
                    map.triangle[i] = static_cast<int>(f);
                }
            }
    }
    return map;
}

double sampleBilinear(const std::vector<double>& field, int width, int height, const Eigen::Vector2d& pixel)
{
    const double fx = std::clamp(pixel.x() - 0.5, 0.0, width - 1.0), fy = std::clamp(pixel.y() - 0.5, 0.0, height - 1.0);
    const int x0 = std::min(static_cast<int>(fx), width - 2), y0 = std::min(static_cast<int>(fy), height - 2);
    const double tx = fx - x0, ty = fy - y0;
    auto at = [&](int x, int y) { return field[static_cast<std::size_t>(y) * width + x]; };
    double sum = 0.0;
    const double w[4] = { (1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty };
    const double v[4] = { at(x0, y0), at(x0 + 1, y0), at(x0, y0 + 1), at(x0 + 1, y0 + 1) };
    for (int k = 0; k < 4; ++k)
        if (w[k] > 0.0)
            sum += w[k] * v[k]; // a NaN with weight 0 is not used
    return sum;
}

} // namespace facesketch::registration

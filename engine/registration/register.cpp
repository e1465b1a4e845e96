#include "registration/register.h"

#include "core/error.h"
#include "geometry/normals.h"
#include "registration/rbf.h"
#include "registration/surface_query.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numbers>

namespace facesketch::registration {

namespace {

// The difference field D faded beyond the pixels that hold it: each pixel without data takes
// the value of the nearest pixel with data (nearest by a breadth-first sweep, distance
// Euclidean to that pixel) times max(0, 1 - distance / blend). `reach` gets that distance (0
// on data, infinity beyond the blend).
std::vector<double> blendBeyondData(const std::vector<double>& D, int width, int height, double blend, std::vector<double>& reach)
{
    const std::size_t n = D.size();
    std::vector<int> source(n, -1);
    reach.assign(n, std::numeric_limits<double>::infinity());
    std::deque<int> queue;
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isnan(D[i])) {
            source[i] = static_cast<int>(i);
            reach[i] = 0.0;
            queue.push_back(static_cast<int>(i));
        }
    while (!queue.empty()) {
        const int i = queue.front();
        queue.pop_front();
        const int x = i % width, y = i / width;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= width || ny >= height)
                    continue;
                const int j = ny * width + nx;
                const int s = source[static_cast<std::size_t>(i)];
                const double d = std::hypot(nx - s % width, ny - s / width);
                if (d < reach[static_cast<std::size_t>(j)] && d < blend) {
                    const bool fresh = source[static_cast<std::size_t>(j)] < 0;
                    reach[static_cast<std::size_t>(j)] = d;
                    source[static_cast<std::size_t>(j)] = s;
                    if (fresh)
                        queue.push_back(j);
                }
            }
    }
    std::vector<double> out(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        if (source[i] >= 0)
            out[i] = D[static_cast<std::size_t>(source[i])] * std::max(0.0, 1.0 - reach[i] / blend);
    return out;
}

// The angles of the right and left ear (obs_r, obs_l) about the axis, between which the scan is
// used; the whole circle without them or when options.betweenEars is off.
Eigen::Vector2d earAngles(const Registration& out, const RegistrationOptions& options)
{
    Eigen::Vector2d ears(-std::numbers::pi, std::numbers::pi);
    const auto& names = out.points.names;
    const auto l = std::find(names.begin(), names.end(), "obs_l"), r = std::find(names.begin(), names.end(), "obs_r");
    if (options.betweenEars && l != names.end() && r != names.end()) {
        ears(0) = out.frame.toCylinder(out.points.scanPoints.row(r - names.begin()).transpose())(0);
        ears(1) = out.frame.toCylinder(out.points.scanPoints.row(l - names.begin()).transpose())(0);
    }
    return ears;
}

// Why a vertex is re-placed after the route (register.h, grazing vertices).
enum Grazing : char { Reliable = 0, SnapToScan = 1, FollowOnly = 2 };

// The cosine between the ray from the axis and the normal of an unwrapped triangle (rows of
// (theta, h, r)): the triangle's depth as a plane over arc length (theta times the mean depth)
// and height has gradient g, and the cosine is 1 / sqrt(1 + g^2). 0 for a degenerate triangle.
double rayCosine(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
    const double arc = (a(2) + b(2) + c(2)) / 3.0;
    const Eigen::Vector2d e1((b(0) - a(0)) * arc, b(1) - a(1)), e2((c(0) - a(0)) * arc, c(1) - a(1));
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    if (!(std::abs(det) > 1e-12))
        return 0.0;
    const double d1 = b(2) - a(2), d2 = c(2) - a(2);
    const Eigen::Vector2d gradient((d1 * e2.y() - d2 * e1.y()) / det, (e1.x() * d2 - e2.x() * d1) / det);
    return 1.0 / std::sqrt(1.0 + gradient.squaredNorm());
}

double readThesis(const std::vector<double>& field, int width, int height, const Eigen::Vector2d& pixel, double smoothing)
{
    const int cx = std::clamp(static_cast<int>(std::floor(pixel.x())), 0, width - 1);
    const int cy = std::clamp(static_cast<int>(std::floor(pixel.y())), 0, height - 1);
    const double fx = std::clamp(pixel.x() - cx, 0.0, 1.0), fy = std::clamp(pixel.y() - cy, 0.0, 1.0);
    auto at
        = [&](int x, int y) { return field[static_cast<std::size_t>(std::clamp(y, 0, height - 1)) * width + std::clamp(x, 0, width - 1)]; };
    // Each neighbour weighs by how near the vertex is to it (thesis fig. 3.32).
    const double leftRight = (1.0 - fx) * at(cx - 1, cy) + fx * at(cx + 1, cy);
    const double topBottom = (1.0 - fy) * at(cx, cy - 1) + fy * at(cx, cy + 1);
    return (1.0 - smoothing) * at(cx, cy) + smoothing * 0.5 * (leftRight + topBottom);
}

// `unwrapped` holds the registered vertices only, from template vertex `first` on.
void registerByDepthMaps(const Mesh& scan, const Vertices& scanUnwrapped, const Triangles& templF, const Vertices& unwrapped, int first,
    const RegistrationOptions& options, Registration& out, std::vector<char>& grazing)
{
    out.grid = gridAround(unwrapped, options.mapWidth, options.mapHeight);
    const DepthMap approx = rasterizeDepth(unwrapped, templF, out.grid);
    const DepthMap target = rasterizeDepth(scanUnwrapped, scan.F, out.grid);
    const int W = out.grid.width, H = out.grid.height;
    std::vector<double> D(approx.depth.size(), std::numeric_limits<double>::quiet_NaN());
    const Eigen::Vector2d ears = earAngles(out, options);
    for (std::size_t i = 0; i < D.size(); ++i) {
        const double d = target.depth[i] - approx.depth[i];
        const double theta = out.grid.centre(static_cast<int>(i % W), static_cast<int>(i / W))(0);
        // Either map may be empty (NaN) here: islessequal compares without raising a flag.
        if (std::islessequal(std::abs(d), options.maxDisplacement) && theta >= ears(0) && theta <= ears(1))
            D[i] = d;
    }
    std::vector<double> reach;
    const std::vector<double> merged = blendBeyondData(D, W, H, options.blendPixels, reach);
    const Eigen::Index nv = unwrapped.rows();
    for (Eigen::Index v = 0; v < nv; ++v) {
        const Eigen::Vector3d thr = unwrapped.row(v).transpose();
        const Eigen::Vector2d pixel = out.grid.toPixel(thr(0), thr(1));
        const int px = std::clamp(static_cast<int>(std::floor(pixel.x())), 0, W - 1);
        const int py = std::clamp(static_cast<int>(std::floor(pixel.y())), 0, H - 1);
        const std::size_t p = static_cast<std::size_t>(py) * W + px;
        VertexSource label = reach[p] == 0.0 ? VertexSource::Scan
            : std::isfinite(reach[p])        ? VertexSource::Blended
                                             : VertexSource::Approximation;
        if (std::isgreater(approx.depth[p], thr(2) + options.occlusionTolerance)) // NaN: no approximation there
            label = VertexSource::Occluded;
        out.source[static_cast<std::size_t>(first + v)] = label;
        if (label == VertexSource::Approximation)
            continue; // out.registered already holds the approximation
        if (target.triangle[p] >= 0 && (label == VertexSource::Scan || label == VertexSource::Occluded)) {
            const auto corner = [&](int k) { return Eigen::Vector3d(scanUnwrapped.row(scan.F(target.triangle[p], k)).transpose()); };
            if (rayCosine(corner(0), corner(1), corner(2)) < options.grazingCosine)
                grazing[static_cast<std::size_t>(v)] = label == VertexSource::Scan ? SnapToScan : FollowOnly;
        }
        double r = thr(2);
        if (label == VertexSource::Scan && options.readBack == ReadBack::Plane) {
            // The plane of the scan triangle seen at the vertex's pixel, at the vertex's own
            // (theta, h): exact when the vertex lies over that triangle, and off by the
            // surface's curvature over a fraction of a pixel otherwise, so no aliasing.
            const int f = target.triangle[p];
            Eigen::Vector2d q[3];
            for (int k = 0; k < 3; ++k)
                q[k] = scanUnwrapped.row(scan.F(f, k)).head<2>().transpose();
            const Eigen::Vector2d at = thr.head<2>();
            const double area = (q[1] - q[0]).x() * (q[2] - q[0]).y() - (q[1] - q[0]).y() * (q[2] - q[0]).x();
            auto edge = [&](int i, int j) { return ((q[j] - q[i]).x() * (at - q[i]).y() - (q[j] - q[i]).y() * (at - q[i]).x()) / area; };
            const double planeDepth = edge(1, 2) * scanUnwrapped(scan.F(f, 0), 2) + edge(2, 0) * scanUnwrapped(scan.F(f, 1), 2)
                + edge(0, 1) * scanUnwrapped(scan.F(f, 2), 2);
            r = planeDepth;
            if (!(std::abs(r - thr(2)) <= options.maxDisplacement))
                grazing[static_cast<std::size_t>(v)] = SnapToScan;
        } else if (options.readBack == ReadBack::Thesis) {
            r += readThesis(merged, W, H, pixel, options.smoothing);
        } else {
            r += sampleBilinear(merged, W, H, pixel);
        }
        out.registered.row(first + v) = out.frame.fromCylinder({ thr(0), thr(1), r }).transpose();
    }
}

void registerByProjection(const Vertices& scanUnwrapped, const Triangles& scanF, const Vertices& unwrapped, int first,
    const RegistrationOptions& options, Registration& out, std::vector<char>& grazing)
{
    // Buckets of scan triangles over the unwrapped plane, about 4 pixels of the map each.
    DepthGrid buckets = gridAround(unwrapped, std::max(2, options.mapWidth / 4), std::max(2, options.mapHeight / 4));
    out.grid = gridAround(unwrapped, options.mapWidth, options.mapHeight);
    const int W = buckets.width, H = buckets.height;
    std::vector<std::vector<int>> bucket(static_cast<std::size_t>(W) * H);
    for (Eigen::Index f = 0; f < scanF.rows(); ++f) {
        double t0 = std::numeric_limits<double>::infinity(), t1 = -t0, h0 = t0, h1 = -t0;
        for (int k = 0; k < 3; ++k) {
            const auto v = scanUnwrapped.row(scanF(f, k));
            t0 = std::min(t0, v(0));
            t1 = std::max(t1, v(0));
            h0 = std::min(h0, v(1));
            h1 = std::max(h1, v(1));
        }
        if (t1 - t0 > std::numbers::pi)
            continue; // straddles the seam
        const Eigen::Vector2d a = buckets.toPixel(t0, h1), b = buckets.toPixel(t1, h0);
        if (b.x() < 0 || b.y() < 0 || a.x() >= W || a.y() >= H)
            continue;
        for (int y = std::max(0, static_cast<int>(a.y())); y <= std::min(H - 1, static_cast<int>(b.y())); ++y)
            for (int x = std::max(0, static_cast<int>(a.x())); x <= std::min(W - 1, static_cast<int>(b.x())); ++x)
                bucket[static_cast<std::size_t>(y) * W + x].push_back(static_cast<int>(f));
    }
    const Eigen::Vector2d ears = earAngles(out, options);
    for (Eigen::Index v = 0; v < unwrapped.rows(); ++v) {
        const Eigen::Vector3d thr = unwrapped.row(v).transpose();
        const Eigen::Vector2d pixel = buckets.toPixel(thr(0), thr(1));
        out.source[static_cast<std::size_t>(first + v)] = VertexSource::Approximation;
        if (pixel.x() < 0 || pixel.y() < 0 || pixel.x() >= W || pixel.y() >= H || thr(0) < ears(0) || thr(0) > ears(1))
            continue;
        double best = std::numeric_limits<double>::infinity(), bestR = thr(2);
        int bestF = -1;
        for (const int f : bucket[static_cast<std::size_t>(static_cast<int>(pixel.y())) * W + static_cast<int>(pixel.x())]) {
            Eigen::Vector2d q[3];
            for (int k = 0; k < 3; ++k)
                q[k] = scanUnwrapped.row(scanF(f, k)).head<2>().transpose();
            const Eigen::Vector2d p = thr.head<2>();
            // Eq. 3.7: the barycentric coordinates of p in the unwrapped triangle.
            const double area = (q[1] - q[0]).x() * (q[2] - q[0]).y() - (q[1] - q[0]).y() * (q[2] - q[0]).x();
            if (!(std::abs(area) > 0.0))
                continue;
            auto edge = [&](int i, int j) { return ((q[j] - q[i]).x() * (p - q[i]).y() - (q[j] - q[i]).y() * (p - q[i]).x()) / area; };
            const double w0 = edge(1, 2), w1 = edge(2, 0), w2 = edge(0, 1);
            if (w0 < -1e-12 || w1 < -1e-12 || w2 < -1e-12)
                continue;
            const double r = w0 * scanUnwrapped(scanF(f, 0), 2) + w1 * scanUnwrapped(scanF(f, 1), 2) + w2 * scanUnwrapped(scanF(f, 2), 2);
            if (std::abs(r - thr(2)) < best) {
                best = std::abs(r - thr(2));
                bestR = r;
                bestF = f;
            }
        }
        if (best <= options.maxDisplacement) {
            out.source[static_cast<std::size_t>(first + v)] = VertexSource::Scan;
            out.registered.row(first + v) = out.frame.fromCylinder({ thr(0), thr(1), bestR }).transpose();
            const auto corner = [&](int k) { return Eigen::Vector3d(scanUnwrapped.row(scanF(bestF, k)).transpose()); };
            if (rayCosine(corner(0), corner(1), corner(2)) < options.grazingCosine)
                grazing[static_cast<std::size_t>(v)] = SnapToScan;
        }
    }
}

// The re-placement of grazing vertices (register.h) on the registered range [first, first +
// count), whose triangles (local indices) are F. `grazing` comes from the route; vertices whose
// approximated surface is itself seen edge-on are added here.
void repairGrazing(const SurfaceQuery& surface, const Triangles& F, int first, int count, const RegistrationOptions& options,
    std::vector<char>& grazing, Registration& out)
{
    Mesh approx;
    approx.V = out.approximation.middleRows(first, count);
    approx.F = F;
    const Vertices normals = vertexNormals(approx);
    bool any = false;
    for (int v = 0; v < count; ++v) {
        const VertexSource label = out.source[static_cast<std::size_t>(first + v)];
        char& g = grazing[static_cast<std::size_t>(v)];
        if (g == Reliable && (label == VertexSource::Scan || label == VertexSource::Blended)) {
            const Eigen::Vector3d d = approx.V.row(v).transpose() - out.frame.origin;
            const Eigen::Vector3d radial = d - out.frame.up.dot(d) * out.frame.up;
            if (radial.norm() > 0.0 && std::abs(normals.row(v).dot(radial.normalized())) < options.grazingCosine)
                g = SnapToScan;
        }
        any = any || g != Reliable;
    }
    if (!any)
        return;
    std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(count));
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = F(f, k), b = F(f, (k + 1) % 3);
            neighbours[static_cast<std::size_t>(a)].push_back(b);
            neighbours[static_cast<std::size_t>(b)].push_back(a);
        }
    // The displacement field, fixed where the route was reliable, relaxed (Jacobi steps of the
    // umbrella average) over the grazing vertices. A patch with no reliable rim keeps 0: the
    // approximation.
    Vertices displacement = out.registered.middleRows(first, count) - approx.V;
    for (int v = 0; v < count; ++v)
        if (grazing[static_cast<std::size_t>(v)] != Reliable)
            displacement.row(v).setZero();
    Vertices next = displacement;
    for (int iteration = 0; iteration < 200; ++iteration) {
        for (int v = 0; v < count; ++v) {
            const auto& around = neighbours[static_cast<std::size_t>(v)];
            if (grazing[static_cast<std::size_t>(v)] == Reliable || around.empty())
                continue;
            Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
            for (const int w : around)
                sum += displacement.row(w);
            next.row(v) = sum / static_cast<double>(around.size());
        }
        displacement.swap(next);
    }
    for (int v = 0; v < count; ++v) {
        const char g = grazing[static_cast<std::size_t>(v)];
        if (g == Reliable)
            continue;
        const Eigen::Vector3d placed = (approx.V.row(v) + displacement.row(v)).transpose();
        out.registered.row(first + v) = placed.transpose();
        if (g == FollowOnly)
            continue;
        const ClosestPoint nearest = surface.closest(placed);
        const bool snap = !nearest.onBoundary && nearest.distance <= options.grazingSnap;
        if (snap)
            out.registered.row(first + v) = nearest.point.transpose();
        out.source[static_cast<std::size_t>(first + v)] = snap ? VertexSource::Scan : VertexSource::Blended;
    }
}

// The refinement's correspondences (register.h, refinePasses): template vertices of [first, end)
// that the previous pass read from the scan (not grazing), at least `spacing` mm apart on the template and from
// every point already in the fit, appended to (P, Q) with their registered positions. Taken in
// vertex order, so the choice is deterministic.
void addRefinementPoints(const Vertices& templV, int first, int end, double spacing, const Registration& previous,
    const std::vector<char>& grazing, Vertices& P, Vertices& Q)
{
    std::vector<Eigen::Vector3d> chosen;
    for (Eigen::Index i = 0; i < P.rows(); ++i)
        chosen.emplace_back(P.row(i).transpose());
    const Eigen::Index given = P.rows();
    std::vector<int> added;
    for (int v = first; v < end; ++v) {
        // Grazing vertices snapped to the scan are left out: their depth was not read but guessed.
        if (previous.source[static_cast<std::size_t>(v)] != VertexSource::Scan || grazing[static_cast<std::size_t>(v - first)] != Reliable)
            continue;
        const Eigen::Vector3d p = templV.row(v).transpose();
        if (std::all_of(chosen.begin(), chosen.end(), [&](const Eigen::Vector3d& c) { return (c - p).norm() >= spacing; })) {
            chosen.push_back(p);
            added.push_back(v);
        }
    }
    const Vertices oldP = P.topRows(given), oldQ = Q.topRows(given);
    P.resize(given + static_cast<Eigen::Index>(added.size()), 3);
    Q.resize(P.rows(), 3);
    P.topRows(given) = oldP;
    Q.topRows(given) = oldQ;
    for (std::size_t k = 0; k < added.size(); ++k) {
        P.row(given + static_cast<Eigen::Index>(k)) = templV.row(added[k]);
        Q.row(given + static_cast<Eigen::Index>(k)) = previous.registered.row(added[k]);
    }
}

// Smooths the displacement field registered - approximation over the registered range (local
// triangles F) by `iterations` umbrella steps of weight 1/2. The displacement, not the positions,
// so that the shape the approximation carries is not shrunk; the scan's noise and its detail
// finer than the approximation are averaged alike.
void smoothDisplacement(const Triangles& F, int first, int count, int iterations, Registration& out)
{
    std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(count));
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            neighbours[static_cast<std::size_t>(F(f, k))].push_back(F(f, (k + 1) % 3));
            neighbours[static_cast<std::size_t>(F(f, (k + 1) % 3))].push_back(F(f, k));
        }
    Vertices displacement = out.registered.middleRows(first, count) - out.approximation.middleRows(first, count);
    Vertices next = displacement;
    for (int iteration = 0; iteration < iterations; ++iteration) {
        for (int v = 0; v < count; ++v) {
            const auto& around = neighbours[static_cast<std::size_t>(v)];
            if (around.empty())
                continue;
            Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
            for (const int w : around)
                sum += displacement.row(w);
            next.row(v) = 0.5 * displacement.row(v) + 0.5 * sum / static_cast<double>(around.size());
        }
        displacement.swap(next);
    }
    out.registered.middleRows(first, count) = out.approximation.middleRows(first, count) + displacement;
}

} // namespace

const char* sourceName(VertexSource source)
{
    switch (source) {
    case VertexSource::Scan:
        return "scan";
    case VertexSource::Blended:
        return "blended";
    case VertexSource::Approximation:
        return "approximation";
    case VertexSource::Occluded:
        return "occluded";
    }
    return "?";
}

FeaturePoints landmarkPositions(const Mesh& templ, const std::map<std::string, int>& landmarks)
{
    FeaturePoints out;
    for (const auto& [name, vertex] : landmarks) {
        if (vertex < 0 || vertex >= templ.V.rows())
            fail("template landmark '", name, "': vertex ", vertex, " outside [0, ", templ.V.rows(), ")");
        out[name] = templ.V.row(vertex).transpose();
    }
    return out;
}

void checkRegistrationOptions(const RegistrationOptions& options, Eigen::Index templateVertices, const std::string& where)
{
    if (options.mapWidth < 8 || options.mapHeight < 8)
        fail(where, ": depth maps of ", options.mapWidth, " x ", options.mapHeight, " pixels, at least 8 x 8 needed");
    if (!(options.smoothing >= 0.0 && options.smoothing <= 1.0))
        fail(where, ": smoothing ", options.smoothing, " outside [0, 1]");
    if (!(options.blendPixels > 0.0) || !(options.maxDisplacement > 0.0))
        fail(where, ": blend width and largest displacement must be positive");
    if (std::isnan(options.grazingCosine) || options.grazingCosine < 0.0 || options.grazingCosine >= 1.0 || std::isnan(options.grazingSnap)
        || options.grazingSnap <= 0.0)
        fail(where, ": grazing cosine ", options.grazingCosine, " outside [0, 1) or snap distance ", options.grazingSnap, " not positive");
    if (options.smoothingSteps < 0 || options.smoothingSteps > 100)
        fail(where, ": displacement smoothing steps ", options.smoothingSteps, " outside [0, 100]");
    if (options.refinePasses < 0 || options.refinePasses > 4 || !(options.refineSpacing > 0.0) || !std::isfinite(options.refineSpacing))
        fail(where, ": refinement passes ", options.refinePasses, " outside [0, 4] or spacing ", options.refineSpacing, " mm not positive");
    const Eigen::Index end = options.endVertex < 0 ? templateVertices : options.endVertex;
    if (options.firstVertex < 0 || options.firstVertex >= end || end > templateVertices)
        fail(where, ": registered vertices [", options.firstVertex, ", ", end, ") not inside the template's [0, ", templateVertices, ")");
}

Registration registerScan(const Mesh& templ, const FeaturePoints& templatePoints, const Mesh& scan, const FeaturePoints& scanPoints,
    const std::string& scanName, const RegistrationOptions& options)
{
    if (scan.F.rows() == 0 || scan.V.rows() == 0)
        fail(scanName, ": the scan has no triangles");
    validateMesh(scan, scanName);
    validateMesh(templ, "the template");
    checkRegistrationOptions(options, templ.V.rows(), scanName);
    const int first = options.firstVertex, end = options.endVertex < 0 ? static_cast<int>(templ.V.rows()) : options.endVertex;
    const SurfaceQuery surface(scan);
    validateFeaturePoints(scanPoints, surface, scanName, options.limits);

    Registration out;
    out.points = completeFeaturePoints(templatePoints, scanPoints, scanName);
    out.frame = frameFromFeaturePoints(out.points.names, out.points.scanPoints);
    const Vertices scanUnwrapped = out.frame.unwrap(scan.V);
    std::vector<int> kept;
    for (Eigen::Index f = 0; f < templ.F.rows(); ++f)
        if (templ.F.row(f).minCoeff() >= first && templ.F.row(f).maxCoeff() < end)
            kept.push_back(static_cast<int>(f));
    if (kept.empty())
        fail(scanName, ": no template triangle among the registered vertices [", first, ", ", end, ")");
    Triangles F(static_cast<Eigen::Index>(kept.size()), 3);
    for (std::size_t i = 0; i < kept.size(); ++i)
        F.row(static_cast<Eigen::Index>(i)) = templ.F.row(kept[i]).array() - first;
    Vertices rbfTemplate = out.points.templatePoints, rbfScan = out.points.scanPoints;
    std::vector<char> grazing;
    for (int pass = 0; pass <= options.refinePasses; ++pass) {
        if (pass > 0)
            addRefinementPoints(templ.V, first, end, options.refineSpacing, out, grazing, rbfTemplate, rbfScan);
        const RbfWarp rbf(rbfTemplate, rbfScan);
        out.approximation = rbf.apply(templ.V);
        out.registered = out.approximation;
        out.source.assign(static_cast<std::size_t>(templ.V.rows()), VertexSource::Approximation);
        const Vertices unwrapped = out.frame.unwrap(out.approximation.middleRows(first, end - first));
        grazing.assign(static_cast<std::size_t>(end - first), Reliable);
        if (options.method == RegistrationMethod::DepthMaps)
            registerByDepthMaps(scan, scanUnwrapped, F, unwrapped, first, options, out, grazing);
        else
            registerByProjection(scanUnwrapped, scan.F, unwrapped, first, options, out, grazing);
        if (options.grazingCosine > 0.0)
            repairGrazing(surface, F, first, end - first, options, grazing, out);
        out.refinementPoints = static_cast<int>(rbfTemplate.rows() - out.points.templatePoints.rows());
    }
    if (options.smoothingSteps > 0)
        smoothDisplacement(F, first, end - first, options.smoothingSteps, out);
    return out;
}

} // namespace facesketch::registration

#include "sketch/simulate.h"

#include "contours/candidates.h"
#include "contours/contour_lines.h"
#include "contours/curvature.h"
#include "core/error.h"
#include "core/random.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

namespace facesketch::sketch {

namespace {

using Polyline = std::vector<Eigen::Vector2d>;

double length(const Polyline& q)
{
    double s = 0;
    for (size_t i = 1; i < q.size(); ++i)
        s += (q[i] - q[i - 1]).norm();
    return s;
}

// A point at arc length t along q, continued straight past either end along the end's
// direction (over the last `reach` pixels), for overshooting strokes.
class ArcLength {
public:
    explicit ArcLength(const Polyline& q)
        : q_(q)
    {
        s_.push_back(0);
        for (size_t i = 1; i < q.size(); ++i)
            s_.push_back(s_.back() + (q[i] - q[i - 1]).norm());
        start_ = direction(true);
        end_ = direction(false);
    }
    double total() const { return s_.back(); }
    /// Arc length at point i of the polyline.
    double arcAt(size_t i) const { return s_[i]; }
    Eigen::Vector2d at(double t) const
    {
        if (t <= 0)
            return q_.front() + t * start_;
        if (t >= total())
            return q_.back() + (t - total()) * end_;
        const size_t i = static_cast<size_t>(std::upper_bound(s_.begin(), s_.end(), t) - s_.begin());
        const double span = s_[i] - s_[i - 1];
        const double u = span > 0 ? (t - s_[i - 1]) / span : 0;
        return (1 - u) * q_[i - 1] + u * q_[i];
    }

private:
    Eigen::Vector2d direction(bool atStart) const
    {
        constexpr double reach = 10; // pixels
        const size_t n = q_.size();
        Eigen::Vector2d a = atStart ? q_[0] : q_[n - 1];
        Eigen::Vector2d b = a;
        for (size_t k = 1; k < n; ++k) {
            b = atStart ? q_[k] : q_[n - 1 - k];
            if ((b - a).norm() >= reach)
                break;
        }
        const Eigen::Vector2d d = a - b; // outwards at either end
        return d.norm() > 0 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d(0, 0);
    }
    const Polyline& q_;
    std::vector<double> s_;
    Eigen::Vector2d start_, end_;
};

// Silhouette segments (pairs of endpoints) chained into polylines through shared endpoints.
std::vector<std::vector<glm::vec3>> chain(const std::vector<glm::vec3>& segments)
{
    const size_t n = segments.size() / 2;
    auto key = [](const glm::vec3& p) {
        // Both triangles of an edge interpolate the same crossing; 1e-3 mm buckets join them.
        auto q = [](float x) { return static_cast<std::int64_t>(std::llround(static_cast<double>(x) * 1000.0)) & 0x1fffff; };
        return (static_cast<std::uint64_t>(q(p.x)) << 42) | (static_cast<std::uint64_t>(q(p.y)) << 21) | static_cast<std::uint64_t>(q(p.z));
    };
    std::unordered_map<std::uint64_t, std::vector<size_t>> at; // endpoint -> segment ends (2 s + end)
    for (size_t e = 0; e < 2 * n; ++e)
        at[key(segments[e])].push_back(e);
    std::vector<bool> used(n, false);
    std::vector<std::vector<glm::vec3>> chains;
    // Next unused segment end sharing the point of end e, or npos.
    auto follow = [&](size_t e) -> size_t {
        for (size_t other : at[key(segments[e])])
            if (!used[other / 2])
                return other;
        return SIZE_MAX;
    };
    for (size_t s = 0; s < n; ++s) {
        if (used[s])
            continue;
        used[s] = true;
        std::vector<glm::vec3> forward { segments[2 * s], segments[2 * s + 1] };
        for (size_t e = follow(2 * s + 1); e != SIZE_MAX; e = follow(e)) {
            used[e / 2] = true;
            const size_t far = e ^ 1; // the segment's other end
            forward.push_back(segments[far]);
            e = far;
            if (follow(e) == SIZE_MAX)
                break;
        }
        std::vector<glm::vec3> backward;
        for (size_t e = follow(2 * s); e != SIZE_MAX; e = follow(e)) {
            used[e / 2] = true;
            const size_t far = e ^ 1;
            backward.push_back(segments[far]);
            e = far;
            if (follow(e) == SIZE_MAX)
                break;
        }
        std::reverse(backward.begin(), backward.end());
        backward.insert(backward.end(), forward.begin(), forward.end());
        chains.push_back(std::move(backward));
    }
    return chains;
}

bool sharesEdge(const Triangles& F, int a, int b)
{
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const bool hasA = F(f, 0) == a || F(f, 1) == a || F(f, 2) == a;
        const bool hasB = F(f, 0) == b || F(f, 1) == b || F(f, 2) == b;
        if (hasA && hasB)
            return true;
    }
    return false;
}

// A smooth random 2D offset along a stroke (simulate.h, `wanderPx`): in x and in y a zero-mean
// Gaussian process over the arc length with the squared-exponential kernel sigma^2 exp(-d^2 /
// (2 l^2)), approximated by K random Fourier features: sigma sqrt(2 / K) sum cos(w_k t + phi_k)
// with w_k ~ N(0, 1 / l^2) and phi_k uniform in [0, 2 pi) (Rahimi and Recht 2007).
class Wander {
public:
    Wander() = default; // no offset
    Wander(Random& random, double sigmaPx, double lengthPx)
        : scale_(sigmaPx * std::sqrt(2.0 / kFeatures))
    {
        for (int axis = 0; axis < 2; ++axis)
            for (int k = 0; k < kFeatures; ++k) {
                omega_[axis][k] = random.normal() / lengthPx;
                phase_[axis][k] = 2 * std::numbers::pi * random.uniform();
            }
    }
    Eigen::Vector2d at(double arcPx) const
    {
        Eigen::Vector2d out = Eigen::Vector2d::Zero();
        if (scale_ == 0)
            return out;
        for (int axis = 0; axis < 2; ++axis)
            for (int k = 0; k < kFeatures; ++k)
                out[axis] += std::cos(omega_[axis][k] * arcPx + phase_[axis][k]);
        return scale_ * out;
    }

private:
    static constexpr int kFeatures = 16;
    double scale_ = 0;
    double omega_[2][kFeatures] = {};
    double phase_[2][kFeatures] = {};
};

} // namespace

std::map<std::string, std::vector<int>> skinContours(const std::map<std::string, std::vector<int>>& contours, int begin, int end)
{
    std::map<std::string, std::vector<int>> out;
    for (const auto& [name, path] : contours) {
        std::vector<int> local;
        for (int v : path)
            if (v >= begin && v < end)
                local.push_back(v - begin);
        if (local.size() >= 2)
            out[name] = std::move(local);
    }
    return out;
}

Simulation simulateStrokes(const Mesh& face, const Mesh& meanFace, const std::map<std::string, std::vector<int>>& contours,
    const std::vector<std::uint32_t>& flags, const SimulateOptions& o)
{
    const Eigen::Index nv = meanFace.V.rows();
    if (face.V.rows() != nv || face.F.rows() != meanFace.F.rows() || face.F != meanFace.F)
        fail("simulateStrokes: the face has ", face.V.rows(), " vertices and ", face.F.rows(), " triangles, the mean face ", nv, " and ",
            meanFace.F.rows(), " (one topology needed)");
    if (!face.V.allFinite() || !meanFace.V.allFinite())
        fail("simulateStrokes: a vertex is not finite");
    if (o.imageSize <= 0 || !(o.spacingPx > 0) || !(o.speedPxPerMs > 0) || o.maxPieces < 1)
        fail("simulateStrokes: image size, spacing, speed and pieces must be positive (", o.imageSize, ", ", o.spacingPx, ", ",
            o.speedPxPerMs, ", ", o.maxPieces, ")");
    if (!(o.noisePx >= 0) || !std::isfinite(o.noisePx))
        fail("simulateStrokes: noise must be a finite number of pixels >= 0, found ", o.noisePx);
    if (!std::isfinite(o.extreme))
        fail("simulateStrokes: extreme factor not finite");
    // isfinite first: an ordered comparison with NaN raises FE_INVALID, which the sanitizer
    // build traps.
    if (!std::isfinite(o.wanderPx) || o.wanderPx < 0 || !std::isfinite(o.wanderLengthPx) || o.wanderLengthPx <= 0)
        fail("simulateStrokes: wander must be a finite number of pixels >= 0 over a positive length, found ", o.wanderPx, " over ",
            o.wanderLengthPx);
    if (!std::isfinite(o.reversed) || o.reversed < 0 || o.reversed > 1)
        fail("simulateStrokes: reversed must be a probability in [0, 1], found ", o.reversed);
    if (!flags.empty() && static_cast<Eigen::Index>(flags.size()) != nv)
        fail("simulateStrokes: ", flags.size(), " vertex flags for ", nv, " vertices");
    for (const auto& [name, path] : contours)
        for (int v : path)
            if (v < 0 || v >= nv)
                fail("simulateStrokes: contour ", name, ": vertex ", v, " outside [0, ", nv, ")");

    Simulation sim;
    sim.traced.F = face.F;
    // Without exaggeration the traced face is the face itself, bit for bit: mean + (face - mean)
    // rounds wherever a coordinate and the mean's differ in sign or by more than a factor of two.
    sim.traced.V = o.extreme == 1 ? face.V : Vertices(meanFace.V + o.extreme * (face.V - meanFace.V));
    const OrbitView view = frameMeshView(meanFace, o.angles, o.imageSize, o.imageSize);
    const Camera camera = orbitCamera(view);
    const Curvature curvature = estimateCurvature(sim.traced);
    auto screen = [&](const Eigen::Vector3d& x) {
        const glm::dvec3 p = camera.project(glm::dvec3(x.x(), x.y(), x.z()));
        return Eigen::Vector2d(p.x, p.y);
    };
    auto excluded = [&](int v) { return !flags.empty() && (flags[static_cast<size_t>(v)] & VertexExcluded) != 0; };

    // Each feature with, per polyline point, the vertex it traces.
    struct Feature {
        std::string name;
        Polyline line;
        std::vector<int> vertices;
    };
    std::vector<Feature> features;
    for (const auto& [name, path] : contours) {
        Polyline run;
        std::vector<int> runVertices;
        auto flush = [&] {
            if (run.size() >= 2 && length(run) >= o.minLengthPx)
                features.push_back({ name, run, runVertices });
            run.clear();
            runVertices.clear();
        };
        // A loop (eye sockets, nostrils: the last vertex shares an edge with the first) is
        // traced all the way round.
        std::vector<int> walk = path;
        if (path.size() > 2 && sharesEdge(face.F, path.front(), path.back()))
            walk.push_back(path.front());
        for (int v : walk) {
            const Eigen::Vector3d x = sim.traced.V.row(v).transpose();
            const glm::dvec3 toCamera = camera.toCamera(glm::dvec3(x.x(), x.y(), x.z()));
            const double facing
                = curvature.normal(v, 0) * toCamera.x + curvature.normal(v, 1) * toCamera.y + curvature.normal(v, 2) * toCamera.z;
            if (facing > o.facingMin && !excluded(v)) {
                run.push_back(screen(x));
                runVertices.push_back(v);
            } else
                flush();
        }
        flush();
    }

    ContourParams params;
    params.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    params.featureSize = meanEdgeLength(sim.traced);
    const ContourLines lines = contourLines(sim.traced, curvature, camera, params, flags);
    auto nearestVertex = [&](const Eigen::Vector3d& x) {
        Eigen::Index best = 0;
        (sim.traced.V.rowwise() - x.transpose()).rowwise().squaredNorm().minCoeff(&best);
        return static_cast<int>(best);
    };
    std::vector<Feature> silhouettes;
    for (const std::vector<glm::vec3>& c : chain(lines.silhouette)) {
        Feature q { "silhouette", {}, {} };
        for (const glm::vec3& p : c) {
            const Eigen::Vector3d x(p.x, p.y, p.z);
            q.line.push_back(screen(x));
            q.vertices.push_back(nearestVertex(x));
        }
        if (length(q.line) >= o.minLengthPx)
            silhouettes.push_back(std::move(q));
    }
    std::sort(silhouettes.begin(), silhouettes.end(), [](const Feature& a, const Feature& b) { return length(a.line) > length(b.line); });
    for (size_t i = 0; i < silhouettes.size() && static_cast<int>(i) < o.silhouettes; ++i)
        features.push_back(std::move(silhouettes[i]));

    Random random(o.seed);
    Random direction(o.seed ^ 0x7265766572736564ULL); // "reversed": its own stream, see simulate.h
    Random wandering(o.seed ^ 0x77616e646572ULL);     // "wander": likewise
    for (const auto& [name, line, lineVertices] : features) {
        const ArcLength arc(line);
        const double total = arc.total();
        int pieces = 1 + static_cast<int>(random.uniform() * o.maxPieces);
        pieces = std::clamp(pieces, 1, std::max(1, static_cast<int>(total / (3 * o.minLengthPx))));
        pieces = std::min(pieces, o.maxPieces);
        std::vector<double> cuts { 0 };
        for (int k = 1; k < pieces; ++k)
            cuts.push_back(total * (k + 0.2 * (random.uniform() - 0.5)) / pieces);
        cuts.push_back(total);
        for (int k = 0; k < pieces; ++k) {
            const double overlap = 0.03 * total;
            double a = k == 0 ? 0 : cuts[k] - overlap;
            double b = k + 1 == pieces ? total : cuts[k + 1] + overlap;
            const double span = b - a;
            // Each end on its own: partial (stops short) or overshooting.
            a += random.uniform() < 0.5 ? random.uniform() * o.trim * span : -random.uniform() * o.overshoot * span;
            b += random.uniform() < 0.5 ? -random.uniform() * o.trim * span : random.uniform() * o.overshoot * span;
            SimulatedStroke s;
            s.feature = name;
            // The vertices whose points lie within the drawn piece (before its jitter).
            for (size_t i = 0; i < line.size(); ++i) {
                const double at = arc.arcAt(i);
                if (at >= a && at <= b && (s.vertices.empty() || s.vertices.back() != lineVertices[i]))
                    s.vertices.push_back(lineVertices[i]);
            }
            s.stroke.view = view;
            s.stroke.surface = Surface::Face;
            const Wander wander = o.wanderPx > 0 ? Wander(wandering, o.wanderPx, o.wanderLengthPx) : Wander();
            double t = a, drawn = 0;
            Eigen::Vector2d last = arc.at(a);
            while (true) {
                const Eigen::Vector2d p = arc.at(t) + wander.at(t - a);
                drawn += (p - last).norm();
                last = p;
                StrokePoint q;
                q.x = p.x() + o.noisePx * random.normal();
                q.y = p.y() + o.noisePx * random.normal();
                q.timeMs = drawn / o.speedPxPerMs;
                s.stroke.points.push_back(q);
                if (t >= b)
                    break;
                t = std::min(b, t + o.spacingPx * (0.5 + random.uniform()));
            }
            if (o.reversed > 0 && direction.uniform() < o.reversed) {
                // The same points drawn from the other end, at the same pen speed.
                const double duration = *s.stroke.points.back().timeMs;
                std::reverse(s.stroke.points.begin(), s.stroke.points.end());
                for (StrokePoint& q : s.stroke.points)
                    q.timeMs = duration - *q.timeMs;
                std::reverse(s.vertices.begin(), s.vertices.end());
            }
            if (s.stroke.points.size() >= 2)
                sim.strokes.push_back(std::move(s));
        }
    }
    return sim;
}

} // namespace facesketch::sketch

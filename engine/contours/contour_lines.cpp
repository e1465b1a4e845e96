#include "contours/contour_lines.h"

#include "core/error.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace facesketch {

namespace {

glm::vec3 lerp(const Mesh& mesh, int a, int b, double t)
{
    const Eigen::RowVector3d p = mesh.V.row(a) + t * (mesh.V.row(b) - mesh.V.row(a));
    return { p.x(), p.y(), p.z() };
}

// Where `f` crosses zero on the edges of triangle t: the edge (a, b) and the zero's parameter s
// along it, at most two; returns how many.
struct Crossing {
    int a, b;
    double s;
};
int zeroCrossings(const Mesh& mesh, Eigen::Index t, const std::vector<double>& f, std::array<Crossing, 2>& out)
{
    int found = 0;
    for (int e = 0; e < 3 && found < 2; ++e) {
        const int a = mesh.F(t, e), b = mesh.F(t, (e + 1) % 3);
        if ((f[a] < 0) != (f[b] < 0))
            out[found++] = { a, b, f[a] / (f[a] - f[b]) };
    }
    return found;
}

// Appends the segment where `f` crosses zero inside triangle t, if `keep` accepts the
// interpolated crossing points (given the edge and parameter).
template <typename Keep>
void traceZero(const Mesh& mesh, Eigen::Index t, const std::vector<double>& f, std::vector<glm::vec3>& out, Keep keep)
{
    std::array<Crossing, 2> c;
    if (zeroCrossings(mesh, t, f, c) != 2 || !keep(c[0].a, c[0].b, c[0].s) || !keep(c[1].a, c[1].b, c[1].s))
        return;
    out.push_back(lerp(mesh, c[0].a, c[0].b, c[0].s));
    out.push_back(lerp(mesh, c[1].a, c[1].b, c[1].s));
}

// rtsc's filter (contours/candidates.h, SuggestiveFilter::RtscCrossing) on the zero segment of
// k_r in triangle t: num and den of tan(theta) D_w k_r l^2 - threshold interpolate linearly to
// the segment's ends and along it, and the part where both are positive is appended: an
// interval, as each is positive on one side of a point.
void traceSuggestiveRtsc(const Mesh& mesh, Eigen::Index t, const std::vector<double>& kr, const std::vector<double>& num,
    const std::vector<double>& den, std::vector<glm::vec3>& out)
{
    std::array<Crossing, 2> c;
    if (zeroCrossings(mesh, t, kr, c) != 2)
        return;
    std::array<glm::vec3, 2> ends;
    std::array<double, 2> n {}, d {};
    for (int i = 0; i < 2; ++i) {
        const auto [a, b, s] = c[i];
        ends[i] = lerp(mesh, a, b, s);
        n[i] = num[a] + s * (num[b] - num[a]);
        d[i] = den[a] + s * (den[b] - den[a]);
    }
    // f(x) = f0 + x (f1 - f0) > 0 on x in [0, 1]: clip [lo, hi] to where it holds. The zero
    // is computed only where f changes sign, so f0 - f1 is not zero.
    double lo = 0, hi = 1;
    for (const auto& f : { n, d }) {
        if (f[0] <= 0 && f[1] <= 0)
            return;
        if (f[0] <= 0)
            lo = std::max(lo, f[0] / (f[0] - f[1]));
        else if (f[1] <= 0)
            hi = std::min(hi, f[0] / (f[0] - f[1]));
    }
    if (!(hi > lo))
        return;
    out.push_back(ends[0] + float(lo) * (ends[1] - ends[0]));
    out.push_back(ends[0] + float(hi) * (ends[1] - ends[0]));
}

} // namespace

ContourLines contourLines(const Mesh& mesh, const Curvature& c, const Camera& camera, const ContourParams& params,
    const std::vector<std::uint32_t>& flags, const std::map<std::string, std::vector<int>>& labelled)
{
    const Eigen::Index nv = mesh.V.rows();
    if (c.k1.size() != nv)
        fail("contourLines: curvature of ", c.k1.size(), " vertices for a mesh of ", nv);
    if (!flags.empty() && static_cast<Eigen::Index>(flags.size()) != nv)
        fail("contourLines: ", flags.size(), " vertex flags for ", nv, " vertices");

    std::vector<double> ndotv(nv), kr(nv), strength(nv), rtscNum(nv);
    const double l2 = params.featureSize * params.featureSize;
    for (Eigen::Index v = 0; v < nv; ++v) {
        const glm::dvec3 to = camera.toCamera({ mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2) });
        const RadialCurvature r = radialCurvature(c, v, Eigen::Vector3d(to.x, to.y, to.z));
        ndotv[v] = r.ndotv;
        kr[v] = r.kr;
        strength[v] = r.dwkr * l2;
        rtscNum[v] = l2 * r.rtscNumerator - params.rtscThreshold * r.ndotv;
    }
    const bool rtsc = params.suggestiveFilter == SuggestiveFilter::RtscCrossing;
    if (rtsc && !(params.rtscThreshold >= 0 && std::isfinite(params.rtscThreshold)))
        fail("contourLines: rtsc threshold ", params.rtscThreshold, " must be finite and not negative");
    auto interpolated = [](const std::vector<double>& g, int a, int b, double s) { return g[a] + s * (g[b] - g[a]); };

    ContourLines lines;
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
        if (!flags.empty() && ((flags[mesh.F(t, 0)] | flags[mesh.F(t, 1)] | flags[mesh.F(t, 2)]) & VertexExcluded))
            continue;
        traceZero(mesh, t, ndotv, lines.silhouette, [](int, int, double) { return true; });
        if (rtsc)
            traceSuggestiveRtsc(mesh, t, kr, rtscNum, ndotv, lines.suggestive);
        else
            traceZero(mesh, t, kr, lines.suggestive, [&](int a, int b, double s) {
                return interpolated(ndotv, a, b, s) > 0 && interpolated(strength, a, b, s) > params.suggestiveThreshold;
            });
    }
    for (const auto& [name, path] : labelled)
        for (size_t i = 0; i + 1 < path.size(); ++i) {
            const int a = path[i], b = path[i + 1];
            if (a < 0 || b < 0 || a >= nv || b >= nv)
                fail("contourLines: labelled contour '", name, "' has vertex ", std::min(a, b) < 0 ? std::min(a, b) : std::max(a, b),
                    " outside [0, ", nv, ")");
            if (ndotv[a] > -params.silhouetteThreshold && ndotv[b] > -params.silhouetteThreshold) {
                lines.labelled.push_back(lerp(mesh, a, a, 0));
                lines.labelled.push_back(lerp(mesh, b, b, 0));
            }
        }
    return lines;
}

} // namespace facesketch

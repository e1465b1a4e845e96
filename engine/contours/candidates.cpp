#include "contours/candidates.h"

#include "core/error.h"
#include "geometry/wedges.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace facesketch {

namespace {
// Isolated and zero-area vertices have a zero normal: no tangent plane, no contour.
bool hasTangentPlane(const Curvature& c, Eigen::Index v)
{
    return c.normal.row(v).squaredNorm() > 0;
}
} // namespace

double defaultSilhouetteThreshold(std::int64_t vertexCount)
{
    if (vertexCount <= 0)
        fail("defaultSilhouetteThreshold: vertex count ", vertexCount, " must be positive");
    return 0.14 * std::sqrt(863.0 / static_cast<double>(vertexCount));
}

double meanEdgeLength(const Mesh& mesh)
{
    std::set<std::pair<int, int>> edges;
    double sum = 0;
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
        for (int c = 0; c < 3; ++c) {
            const int a = mesh.F(t, c), b = mesh.F(t, (c + 1) % 3);
            if (edges.insert(std::minmax(a, b)).second)
                sum += (mesh.V.row(a) - mesh.V.row(b)).norm();
        }
    if (edges.empty())
        fail("meanEdgeLength: the mesh has no edges");
    return sum / static_cast<double>(edges.size());
}

std::vector<Candidate> contourCandidates(const std::vector<Mesh>& meshes, const std::vector<Curvature>& curv,
    const std::vector<std::uint32_t>& flags, const Camera& camera, const ContourParams& p,
    std::vector<std::pair<std::uint32_t, std::uint32_t>>* nearTies, double tol)
{
    if (meshes.size() != curv.size())
        fail("contourCandidates: ", meshes.size(), " meshes but ", curv.size(), " curvatures");
    if (meshes.empty())
        return {};
    const Eigen::Index nv = meshes[0].V.rows();
    if (!flags.empty() && static_cast<Eigen::Index>(flags.size()) != nv)
        fail("contourCandidates: ", flags.size(), " vertex flags for ", nv, " vertices");
    if (p.suggestiveFilter == SuggestiveFilter::RtscCrossing && !(p.rtscThreshold >= 0 && std::isfinite(p.rtscThreshold)))
        fail("contourCandidates: rtsc threshold ", p.rtscThreshold, " must be finite and not negative");
    const Wedges wedges = buildWedges(meshes[0].F, nv);
    const double l2 = p.featureSize * p.featureSize;

    std::vector<Candidate> out;
    std::vector<RadialCurvature> rc(nv);
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Mesh& mesh = meshes[m];
        const Curvature& c = curv[m];
        if (mesh.V.rows() != nv || c.k1.size() != nv)
            fail("contourCandidates: mesh ", m, " has ", mesh.V.rows(), " vertices and ", c.k1.size(), " curvatures, expected ", nv);
        for (Eigen::Index v = 0; v < nv; ++v) {
            const glm::dvec3 to = camera.toCamera({ mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2) });
            rc[v] = radialCurvature(c, v, Eigen::Vector3d(to.x, to.y, to.z));
        }
        for (Eigen::Index v = 0; v < nv; ++v) {
            const std::uint32_t flag = flags.empty() ? 0 : flags[v];
            if ((flag & VertexExcluded) || !hasTangentPlane(c, v))
                continue;
            const RadialCurvature& r = rc[v];
            bool tie = false;
            std::uint32_t types = 0;

            if (std::abs(r.ndotv) < p.silhouetteThreshold)
                types |= ContourSilhouette;
            tie |= std::abs(std::abs(r.ndotv) - p.silhouetteThreshold) < tol;

            const bool rtsc = p.suggestiveFilter == SuggestiveFilter::RtscCrossing;
            const double strength = r.dwkr * l2;
            tie |= std::abs(r.ndotv) < tol;
            if (!rtsc)
                tie |= std::abs(strength - p.suggestiveThreshold) < tol * p.suggestiveThreshold;
            if (r.ndotv > 0 && (rtsc || strength > p.suggestiveThreshold)) {
                const double scale = std::abs(c.k1[v]) + std::abs(c.k2[v]);
                for (std::uint32_t w = wedges.offsets[v]; w < wedges.offsets[v + 1]; ++w)
                    for (const std::uint32_t u : wedges.corners[w]) {
                        if (!hasTangentPlane(c, u))
                            continue;
                        const double a = rc[v].kr, b = rc[u].kr;
                        const bool crossing = (a < 0) != (b < 0);
                        const bool nearer = std::abs(a) < std::abs(b) || (std::abs(a) == std::abs(b) && static_cast<std::uint32_t>(v) < u);
                        bool passes = true;
                        if (rtsc && crossing && nearer) {
                            // rtsc's test where k_r is zero on the edge: num / den > threshold
                            // with num = l^2 rtscNumerator - threshold n.v, den = n.v.
                            const double t = a / (a - b);
                            const double numV = l2 * rc[v].rtscNumerator - p.rtscThreshold * rc[v].ndotv;
                            const double numU = l2 * rc[u].rtscNumerator - p.rtscThreshold * rc[u].ndotv;
                            const double num = (1 - t) * numV + t * numU, den = (1 - t) * rc[v].ndotv + t * rc[u].ndotv;
                            passes = num > 0 && den > 0;
                            const double numScale = (1 - t) * (std::abs(l2 * rc[v].rtscNumerator) + p.rtscThreshold * std::abs(rc[v].ndotv))
                                + t * (std::abs(l2 * rc[u].rtscNumerator) + p.rtscThreshold * std::abs(rc[u].ndotv));
                            tie |= std::abs(num) < tol * numScale || std::abs(den) < tol;
                        }
                        if (crossing && nearer && passes)
                            types |= ContourSuggestive;
                        tie |= std::abs(a) < tol * scale || std::abs(b) < tol * scale
                            || (crossing && std::abs(std::abs(a) - std::abs(b)) < tol * scale);
                    }
            }

            if ((flag & VertexLabelled) && r.ndotv > -p.silhouetteThreshold)
                types |= ContourLabelled;
            tie |= (flag & VertexLabelled) && std::abs(r.ndotv + p.silhouetteThreshold) < tol;

            if (types == 0) {
                if (tie && nearTies)
                    nearTies->push_back({ static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(v) });
                continue;
            }
            const glm::dvec3 world(mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2));
            const glm::dvec3 s = camera.project(world);
            const double dist = glm::length(world - glm::dvec3(p.sphere[0], p.sphere[1], p.sphere[2]));
            const double pxTol = 1e-2;
            tie |= std::abs(s.x - p.rect[0]) < pxTol || std::abs(s.x - p.rect[2]) < pxTol || std::abs(s.y - p.rect[1]) < pxTol
                || std::abs(s.y - p.rect[3]) < pxTol || std::abs(dist - p.sphere[3]) < tol * p.sphere[3];
            if (tie && nearTies)
                nearTies->push_back({ static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(v) });
            if (s.x < p.rect[0] || s.x > p.rect[2] || s.y < p.rect[1] || s.y > p.rect[3] || dist > p.sphere[3])
                continue;
            Candidate cand;
            cand.mesh = static_cast<std::uint32_t>(m);
            cand.vertex = static_cast<std::uint32_t>(v);
            cand.types = types;
            for (int k = 0; k < 3; ++k)
                cand.world[k] = static_cast<float>(world[k]);
            cand.screen[0] = static_cast<float>(s.x);
            cand.screen[1] = static_cast<float>(s.y);
            cand.depth = static_cast<float>(s.z);
            out.push_back(cand);
        }
    }
    return out;
}

} // namespace facesketch

#include "sketch/symmetry.h"

#include "contours/candidates.h"
#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <unordered_map>

namespace facesketch::sketch {

namespace {

// Candidate partners per vertex: enough that a vertex whose nearest mirror neighbour was
// taken by a closer pair still finds its own.
constexpr int kCandidates = 4;

// The k nearest vertices of each query point through a uniform 3D grid of `cell` mm.
class Grid3 {
public:
    Grid3(const Vertices& V, double cell)
        : V_(V)
        , cell_(cell)
    {
        for (Eigen::Index v = 0; v < V.rows(); ++v)
            cells_[key(V.row(v).transpose())].push_back(static_cast<int>(v));
    }

    std::vector<std::pair<double, int>> nearest(const Eigen::Vector3d& q, int k) const
    {
        std::vector<std::pair<double, int>> found;
        const auto [cx, cy, cz] = coords(q);
        for (long ring = 0;; ++ring) {
            // Points in ring r or beyond lie at least (r - 1) cells from the query.
            if (static_cast<int>(found.size()) >= k && found[static_cast<size_t>(k) - 1].first <= static_cast<double>(ring - 1) * cell_)
                break;
            if (ring > 64) // the rest of the mesh is far away: what was found is the answer
                break;
            for (long x = cx - ring; x <= cx + ring; ++x)
                for (long y = cy - ring; y <= cy + ring; ++y)
                    for (long z = cz - ring; z <= cz + ring; ++z) {
                        if (std::max({ std::abs(x - cx), std::abs(y - cy), std::abs(z - cz) }) != ring)
                            continue;
                        const auto it = cells_.find(pack(x, y, z));
                        if (it == cells_.end())
                            continue;
                        for (int v : it->second)
                            found.push_back({ (V_.row(v).transpose() - q).norm(), v });
                    }
            std::sort(found.begin(), found.end());
            if (static_cast<int>(found.size()) > 4 * k)
                found.resize(static_cast<size_t>(4 * k));
        }
        if (static_cast<int>(found.size()) > k)
            found.resize(static_cast<size_t>(k));
        return found;
    }

private:
    std::tuple<long, long, long> coords(const Eigen::Vector3d& p) const
    {
        return { std::lround(std::floor(p.x() / cell_)), std::lround(std::floor(p.y() / cell_)), std::lround(std::floor(p.z() / cell_)) };
    }
    static std::uint64_t pack(long x, long y, long z)
    {
        auto u = [](long a) { return static_cast<std::uint64_t>(a + (1L << 20)) & 0x1fffff; };
        return (u(x) << 42) | (u(y) << 21) | u(z);
    }
    std::uint64_t key(const Eigen::Vector3d& p) const
    {
        const auto [x, y, z] = coords(p);
        return pack(x, y, z);
    }

    const Vertices& V_;
    double cell_;
    std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace

Eigen::Matrix3d MirrorMap::reflection() const
{
    return Eigen::Matrix3d::Identity() - 2 * check_.normal * check_.normal.transpose();
}

MirrorMap MirrorMap::find(
    const Mesh& face, const std::map<std::string, int>& landmarks, const std::string& what, double tolerance, double maxUnpaired)
{
    const Eigen::Index nv = face.V.rows();
    if (nv == 0 || face.F.rows() == 0)
        fail(what, ": no mesh to find a mirror map of");
    if (!face.V.allFinite())
        fail(what, ": the mesh has a non-finite vertex");
    std::vector<std::pair<int, int>> labelled;
    for (const auto& [name, v] : landmarks) {
        if (!endsWith(name, "_l"))
            continue;
        const auto right = landmarks.find(name.substr(0, name.size() - 2) + "_r");
        if (right == landmarks.end())
            continue;
        if (v < 0 || v >= nv || right->second < 0 || right->second >= nv)
            fail(what, ": landmark ", name, " or its _r partner outside [0, ", nv, ")");
        labelled.push_back({ v, right->second });
    }

    MirrorMap map;
    MirrorCheck& check = map.check_;
    check.meanEdge = meanEdgeLength(face);
    if (!labelled.empty()) {
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        for (const auto& [l, r] : labelled)
            n += (face.V.row(l) - face.V.row(r)).transpose().normalized();
        check.normal = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitX();
        // The median midpoint: one mislabelled pair must not move the plane.
        std::vector<double> mid;
        for (const auto& [l, r] : labelled)
            mid.push_back(0.5 * (face.V.row(l) + face.V.row(r)).dot(check.normal.transpose()));
        std::sort(mid.begin(), mid.end());
        check.planeX = mid.size() % 2 ? mid[mid.size() / 2] : 0.5 * (mid[mid.size() / 2 - 1] + mid[mid.size() / 2]);
    } else {
        check.planeX = face.V.col(0).mean();
    }
    // Each vertex's own mean edge length: the tolerance follows the mesh's local density.
    Eigen::VectorXd localEdge = Eigen::VectorXd::Zero(nv), edges = Eigen::VectorXd::Zero(nv);
    for (Eigen::Index f = 0; f < face.F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = face.F(f, k), b = face.F(f, (k + 1) % 3);
            const double l = (face.V.row(a) - face.V.row(b)).norm();
            localEdge[a] += l;
            localEdge[b] += l;
            edges[a] += 1;
            edges[b] += 1;
        }
    for (Eigen::Index v = 0; v < nv; ++v)
        localEdge[v] = edges[v] > 0 ? localEdge[v] / edges[v] : check.meanEdge;

    const Grid3 grid(face.V, std::max(check.meanEdge, 1e-9));
    std::vector<std::tuple<double, int, int>> pairs;
    pairs.reserve(static_cast<size_t>(nv) * kCandidates);
    for (Eigen::Index v = 0; v < nv; ++v) {
        const Eigen::Vector3d m = map.mirror(face.V.row(v).transpose());
        for (const auto& [d, w] : grid.nearest(m, kCandidates))
            pairs.push_back({ d, static_cast<int>(v), w });
    }
    // Closest pairs first; (v, w) and (w, v) measure nearly the same, either pairs both.
    std::sort(pairs.begin(), pairs.end());
    const std::uint32_t none = kNone;
    map.partner_.assign(static_cast<size_t>(nv), none);
    for (const auto& [d, v, w] : pairs) {
        if (map.partner_[v] != none || map.partner_[w] != none)
            continue;
        map.partner_[v] = static_cast<std::uint32_t>(w);
        map.partner_[w] = static_cast<std::uint32_t>(v);
    }
    // Vertices whose candidates were all taken by closer pairs: paired among themselves, each
    // with the free vertex nearest its mirror image, closest first (few, so directly).
    std::vector<int> left;
    for (Eigen::Index v = 0; v < nv; ++v)
        if (map.partner_[v] == none)
            left.push_back(static_cast<int>(v));
    if (static_cast<Eigen::Index>(left.size()) > std::max<Eigen::Index>(64, nv / 20))
        fail(what, ": ", left.size(), " vertices (vertex ", left.front(),
            " first) have no vertex near their mirror image about x = ", check.planeX, ": the face is not left-right symmetric");
    std::vector<std::tuple<double, int, int>> late;
    for (int v : left)
        for (int w : left)
            late.push_back({ (map.mirror(face.V.row(v).transpose()) - face.V.row(w).transpose()).norm(), v, w });
    std::sort(late.begin(), late.end());
    for (const auto& [d, v, w] : late) {
        if (map.partner_[v] != none || map.partner_[w] != none)
            continue;
        map.partner_[v] = static_cast<std::uint32_t>(w);
        map.partner_[w] = static_cast<std::uint32_t>(v);
    }
    // Pairs further apart than the tolerance are dissolved: on a region cut unevenly at its
    // border (an ICT-FaceKit import) a few border vertices have no true partner, and mirroring
    // onto a wrong one would be worse than not mirroring.
    auto distance
        = [&](Eigen::Index v) { return (map.mirror(face.V.row(v).transpose()) - face.V.row(map.partner_[v]).transpose()).norm(); };
    for (Eigen::Index v = 0; v < nv; ++v)
        if (map.partner_[v] != none && distance(v) > tolerance * std::max(localEdge[v], localEdge[map.partner_[v]])) {
            map.partner_[map.partner_[v]] = none;
            map.partner_[v] = none;
        }
    double sum = 0;
    int paired = 0;
    for (Eigen::Index v = 0; v < nv; ++v) {
        if (map.partner_[v] == none) {
            ++check.unpaired;
            continue;
        }
        const double d = distance(v);
        sum += d;
        ++paired;
        check.maxDistance = std::max(check.maxDistance, d);
        check.selfPaired += map.partner_[v] == static_cast<std::uint32_t>(v) ? 1 : 0;
    }
    check.meanDistance = paired > 0 ? sum / paired : 0;
    if (check.unpaired > maxUnpaired * static_cast<double>(nv))
        fail(what, ": ", check.unpaired, " of ", nv, " vertices have no partner within ", tolerance, " x their edge length (mean ",
            check.meanEdge, " mm) of their mirror image through the plane n . x = ", check.planeX, " (n = ", check.normal.transpose(),
            "): the topology is not left-right symmetric");
    for (const auto& [l, r] : labelled) {
        if (map.partner_[l] != static_cast<std::uint32_t>(r))
            fail(what, ": the labelled pair ", l, "/", r, " does not map onto itself (vertex ", l, " pairs with ", map.partner_[l], ")");
        ++check.labelledPairs;
    }
    return map;
}

std::map<std::string, int> skinLandmarks(const std::map<std::string, int>& landmarks, int skinBegin, int skinEnd)
{
    std::map<std::string, int> out;
    for (const auto& [name, v] : landmarks)
        if (v >= skinBegin && v < skinEnd)
            out[name] = v - skinBegin;
    return out;
}

} // namespace facesketch::sketch

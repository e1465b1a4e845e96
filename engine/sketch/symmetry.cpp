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
    Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
    S(0, 0) = -1;
    return S;
}

MirrorMap MirrorMap::find(const Mesh& face, const std::map<std::string, int>& landmarks, const std::string& what, double tolerance)
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
        double sum = 0;
        for (const auto& [l, r] : labelled)
            sum += 0.5 * (face.V(l, 0) + face.V(r, 0));
        check.planeX = sum / static_cast<double>(labelled.size());
    } else {
        check.planeX = face.V.col(0).mean();
    }

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
    const std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    map.partner_.assign(static_cast<size_t>(nv), none);
    for (const auto& [d, v, w] : pairs) {
        if (map.partner_[v] != none || map.partner_[w] != none)
            continue;
        map.partner_[v] = static_cast<std::uint32_t>(w);
        map.partner_[w] = static_cast<std::uint32_t>(v);
    }
    double worst = -1, sum = 0;
    Eigen::Index worstVertex = 0;
    for (Eigen::Index v = 0; v < nv; ++v) {
        if (map.partner_[v] == none)
            fail(what, ": vertex ", v, " has no mirror partner among the ", kCandidates,
                " vertices nearest its mirror image (the face is not left-right symmetric about x = ", check.planeX, ")");
        const double d = (map.mirror(face.V.row(v).transpose()) - face.V.row(map.partner_[v]).transpose()).norm();
        sum += d;
        check.selfPaired += map.partner_[v] == static_cast<std::uint32_t>(v) ? 1 : 0;
        if (d > worst) {
            worst = d;
            worstVertex = v;
        }
    }
    check.maxDistance = worst;
    check.meanDistance = sum / static_cast<double>(nv);
    if (worst > tolerance * check.meanEdge)
        fail(what, ": vertex ", worstVertex, " lies ", worst, " mm from the mirror image of its partner ", map.partner_[worstVertex],
            ", more than ", tolerance, " x the mean edge length (", check.meanEdge, " mm): the topology is not left-right symmetric");
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

#include "stats/segmentation.h"

#include "core/error.h"
#include "stats/kmeans.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <string>

namespace facesketch::stats {

namespace {

using Adjacency = std::vector<std::vector<int>>;

Adjacency adjacency(const Mesh& mesh)
{
    Adjacency next(static_cast<size_t>(mesh.vertexCount()));
    for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
            next[static_cast<size_t>(a)].push_back(b);
            next[static_cast<size_t>(b)].push_back(a);
        }
    for (auto& list : next) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    return next;
}

// Ring distance from `sources` (distance 1) to every vertex with `inside(v)` true, up to
// `limit`; 0 where not reached.
template <typename Inside> std::vector<int> ringDistance(const Adjacency& next, const std::vector<int>& sources, Inside inside, int limit)
{
    std::vector<int> distance(next.size(), 0);
    std::deque<int> queue;
    for (int v : sources) {
        distance[static_cast<size_t>(v)] = 1;
        queue.push_back(v);
    }
    while (!queue.empty()) {
        const int v = queue.front();
        queue.pop_front();
        const int dv = distance[static_cast<size_t>(v)];
        if (dv >= limit)
            continue;
        for (int u : next[static_cast<size_t>(v)])
            if (distance[static_cast<size_t>(u)] == 0 && inside(u)) {
                distance[static_cast<size_t>(u)] = dv + 1;
                queue.push_back(u);
            }
    }
    return distance;
}

// Merges every group smaller than minVertices into a neighbour, smallest first: into the
// neighbour sharing most edges among those that stay within maxVertices, else into the
// smallest neighbour, else (no neighbour: a separate mesh component) the nearest centroid.
void mergeSmallGroups(Eigen::VectorXi& label, int groups, const Adjacency& next, const Eigen::MatrixXd& P, const SegmentationOptions& o)
{
    for (;;) {
        Eigen::VectorXi size = Eigen::VectorXi::Zero(groups);
        for (Eigen::Index v = 0; v < label.size(); ++v)
            ++size(label(v));
        int small = -1;
        int alive = 0;
        for (int g = 0; g < groups; ++g) {
            if (size(g) == 0)
                continue;
            ++alive;
            if (size(g) < o.minVertices && (small < 0 || size(g) < size(small)))
                small = g;
        }
        if (small < 0 || alive <= 1)
            return;

        std::map<int, int> shared; // neighbouring group -> edges shared with `small`
        for (Eigen::Index v = 0; v < label.size(); ++v)
            if (label(v) == small)
                for (int u : next[static_cast<size_t>(v)])
                    if (label(u) != small)
                        ++shared[label(u)];
        int into = -1;
        for (const auto& [g, edges] : shared)
            if (size(small) + size(g) <= o.maxVertices && (into < 0 || edges > shared[into]))
                into = g;
        for (const auto& [g, edges] : shared)
            if (into < 0 || (size(small) + size(into) > o.maxVertices && size(g) < size(into)))
                into = g;
        if (into < 0) {
            Eigen::MatrixXd centroid = Eigen::MatrixXd::Zero(groups, 3);
            for (Eigen::Index v = 0; v < label.size(); ++v)
                centroid.row(label(v)) += P.row(v);
            double best = std::numeric_limits<double>::infinity();
            for (int g = 0; g < groups; ++g)
                if (g != small && size(g) > 0) {
                    const double d = (centroid.row(g) / size(g) - centroid.row(small) / size(small)).squaredNorm();
                    if (d < best) {
                        best = d;
                        into = g;
                    }
                }
        }
        for (Eigen::Index v = 0; v < label.size(); ++v)
            if (label(v) == small)
                label(v) = into;
    }
}

} // namespace

Segmentation segmentFace(const Mesh& mean, int noseTip, const SegmentationOptions& o)
{
    validateMesh(mean, "segmentFace: mean face");
    const Eigen::Index nv = mean.vertexCount();
    if (noseTip < 0 || noseTip >= nv)
        fail("segmentFace: nose tip ", noseTip, " outside [0, ", nv, ")");
    if (o.clusters < 1 || o.minVertices < 0 || o.maxVertices < 1 || o.overlapRings < 0)
        fail("segmentFace: options out of range (clusters ", o.clusters, ", minVertices ", o.minVertices, ", maxVertices ", o.maxVertices,
            ", overlapRings ", o.overlapRings, ")");

    Eigen::MatrixXd P = mean.V;
    if (o.mirror)
        P.col(0) = (P.col(0).array() - mean.V(noseTip, 0)).abs();
    KMeansOptions km;
    km.firstSeed = noseTip;
    const int clusters = static_cast<int>(std::min<Eigen::Index>(o.clusters, nv));
    Eigen::VectorXi label = kmeans(P, clusters, km).labels;
    const Adjacency next = adjacency(mean);
    mergeSmallGroups(label, clusters, next, P, o);

    // Number the surviving groups by their lowest vertex.
    std::vector<int> number(static_cast<size_t>(clusters), -1);
    int groups = 0;
    for (Eigen::Index v = 0; v < nv; ++v)
        if (number[static_cast<size_t>(label(v))] < 0)
            number[static_cast<size_t>(label(v))] = groups++;
    Segmentation seg;
    seg.core.resize(nv);
    for (Eigen::Index v = 0; v < nv; ++v)
        seg.core(v) = number[static_cast<size_t>(label(v))];

    const int r = o.overlapRings;
    std::vector<std::vector<double>> raw(static_cast<size_t>(groups));
    Eigen::VectorXd total = Eigen::VectorXd::Zero(nv);
    for (int g = 0; g < groups; ++g) {
        auto inCore = [&](int v) { return seg.core(v) == g; };
        std::vector<int> border, outer;
        for (Eigen::Index v = 0; v < nv; ++v) {
            if (!inCore(static_cast<int>(v)))
                continue;
            for (int u : next[static_cast<size_t>(v)])
                if (!inCore(u)) {
                    border.push_back(static_cast<int>(v));
                    break;
                }
        }
        // Depth inside the core (1 on its border; 0 = deeper than r + 1 rings or no border).
        const std::vector<int> depth = ringDistance(next, border, inCore, r + 1);
        // Rings outside the core: the core's outer neighbours are ring 1.
        for (int v : border)
            for (int u : next[static_cast<size_t>(v)])
                if (!inCore(u))
                    outer.push_back(u);
        std::sort(outer.begin(), outer.end());
        outer.erase(std::unique(outer.begin(), outer.end()), outer.end());
        const std::vector<int> ring = r > 0 ? ringDistance(
                                          next, outer, [&](int v) { return !inCore(v); }, r)
                                            : std::vector<int>(next.size(), 0);

        std::vector<int>& members = seg.vertices.emplace_back();
        for (Eigen::Index v = 0; v < nv; ++v) {
            const auto sv = static_cast<size_t>(v);
            double t = 0.0;
            if (inCore(static_cast<int>(v)))
                t = depth[sv] == 0 ? r + 1.0 : depth[sv] - 0.5;
            else if (ring[sv] > 0)
                t = -(ring[sv] - 0.5);
            else
                continue;
            double w = 1.0;
            if (r > 0) {
                const double u = std::clamp((t + r) / (2.0 * r), 0.0, 1.0);
                w = u * u * (3.0 - 2.0 * u);
            }
            members.push_back(static_cast<int>(v));
            raw[static_cast<size_t>(g)].push_back(w);
            total(v) += w;
        }
    }
    for (int g = 0; g < groups; ++g) {
        const auto& members = seg.vertices[static_cast<size_t>(g)];
        Eigen::VectorXd& w = seg.weights.emplace_back(members.size());
        for (size_t i = 0; i < members.size(); ++i)
            w(static_cast<Eigen::Index>(i)) = raw[static_cast<size_t>(g)][i] / total(members[i]);
    }
    return seg;
}

std::vector<Eigen::Index> segmentCoordinates(const Segmentation& segmentation, int group)
{
    if (group < 0 || group >= segmentation.size())
        fail("segmentCoordinates: group ", group, " outside [0, ", segmentation.size(), ")");
    std::vector<Eigen::Index> coordinates;
    for (int v : segmentation.vertices[static_cast<size_t>(group)])
        for (int c = 0; c < 3; ++c)
            coordinates.push_back(3 * static_cast<Eigen::Index>(v) + c);
    return coordinates;
}

Eigen::VectorXd blendSegments(const Segmentation& segmentation, const std::vector<Eigen::VectorXd>& parts)
{
    if (static_cast<int>(parts.size()) != segmentation.size())
        fail("blendSegments: ", parts.size(), " parts for ", segmentation.size(), " groups");
    Eigen::VectorXd face = Eigen::VectorXd::Zero(3 * segmentation.core.size());
    for (int g = 0; g < segmentation.size(); ++g) {
        const auto& members = segmentation.vertices[static_cast<size_t>(g)];
        const Eigen::VectorXd& part = parts[static_cast<size_t>(g)];
        if (part.size() != 3 * static_cast<Eigen::Index>(members.size()))
            fail("blendSegments: part ", g, " has ", part.size(), " values, expected ", 3 * members.size());
        const Eigen::VectorXd& w = segmentation.weights[static_cast<size_t>(g)];
        for (size_t i = 0; i < members.size(); ++i)
            face.segment<3>(3 * members[i]) += w(static_cast<Eigen::Index>(i)) * part.segment<3>(3 * static_cast<Eigen::Index>(i));
    }
    return face;
}

} // namespace facesketch::stats

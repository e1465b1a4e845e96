#include "geometry/graph.h"

#include "core/error.h"
#include "geometry/wedges.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <queue>
#include <set>

namespace facesketch {

RingDistances::RingDistances(const Triangles& F, Eigen::Index vertexCount, int k)
    : k_(k)
{
    if (k < 0 || k > 250)
        fail("RingDistances: k = ", k, " rings must be in [0, 250]");
    for (Eigen::Index t = 0; t < F.rows(); ++t)
        for (int c = 0; c < 3; ++c)
            if (F(t, c) < 0 || F(t, c) >= vertexCount)
                fail("RingDistances: triangle ", t, " has vertex ", F(t, c), " outside [0, ", vertexCount, ")");
    const Neighbours rings = buildNeighbours(buildWedges(F, vertexCount));
    const std::size_t n = static_cast<std::size_t>(vertexCount);
    offsets_.assign(n + 1, 0);
    // Scratch of the search: hop count per vertex (-1 unvisited), reset after each source.
    std::vector<int> seen(n, -1);
    std::vector<std::uint32_t> frontier, next, visited;
    std::vector<std::pair<std::uint32_t, std::uint8_t>> row;
    for (std::size_t s = 0; s < n; ++s) {
        visited.assign(1, static_cast<std::uint32_t>(s));
        seen[s] = 0;
        frontier.assign(1, static_cast<std::uint32_t>(s));
        // Unit weights: Dijkstra's queue pops whole rings in order, so each ring is one pass.
        for (int h = 1; h <= k && !frontier.empty(); ++h) {
            next.clear();
            for (std::uint32_t v : frontier)
                for (std::uint32_t e = rings.offsets[v]; e < rings.offsets[v + 1]; ++e) {
                    const std::uint32_t w = rings.vertices[e];
                    if (seen[w] < 0) {
                        seen[w] = h;
                        next.push_back(w);
                        visited.push_back(w);
                    }
                }
            frontier.swap(next);
        }
        row.clear();
        for (std::uint32_t v : visited)
            row.push_back({ v, static_cast<std::uint8_t>(seen[v]) });
        std::sort(row.begin(), row.end());
        for (const auto& [v, h] : row) {
            targets_.push_back(v);
            hops_.push_back(h);
            seen[v] = -1;
        }
        if (targets_.size() > std::numeric_limits<std::uint32_t>::max())
            fail("RingDistances: more than 2^32 entries (", vertexCount, " vertices, k = ", k, ")");
        offsets_[s + 1] = static_cast<std::uint32_t>(targets_.size());
    }
}

int RingDistances::hops(std::uint32_t i, std::uint32_t j) const
{
    if (static_cast<std::size_t>(i) + 1 >= offsets_.size() || static_cast<std::size_t>(j) + 1 >= offsets_.size())
        return -1;
    const auto begin = targets_.begin() + offsets_[i], end = targets_.begin() + offsets_[i + 1];
    const auto it = std::lower_bound(begin, end, j);
    if (it == end || *it != j)
        return -1;
    return hops_[static_cast<std::size_t>(it - targets_.begin())];
}

EdgeGraph buildEdgeGraph(const Vertices& V, const Triangles& F, Eigen::Index vertexLimit)
{
    if (vertexLimit < 0 || vertexLimit > V.rows())
        fail("buildEdgeGraph: vertex limit ", vertexLimit, " outside [0, ", V.rows(), "]");
    std::vector<std::set<int>> neighbours(static_cast<std::size_t>(vertexLimit));
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = F(f, k), b = F(f, (k + 1) % 3);
            if (a < 0 || b < 0 || a >= V.rows() || b >= V.rows())
                fail("buildEdgeGraph: triangle ", f, " has a vertex index outside [0, ", V.rows(), ")");
            if (a < vertexLimit && b < vertexLimit) {
                neighbours[static_cast<std::size_t>(a)].insert(b);
                neighbours[static_cast<std::size_t>(b)].insert(a);
            }
        }
    EdgeGraph g;
    g.adjacency.resize(neighbours.size());
    for (std::size_t a = 0; a < neighbours.size(); ++a)
        for (int b : neighbours[a])
            g.adjacency[a].push_back({ b, (V.row(static_cast<Eigen::Index>(a)) - V.row(b)).norm() });
    return g;
}

std::vector<int> shortestPath(const EdgeGraph& graph, int from, int to)
{
    const auto& g = graph.adjacency;
    const int n = static_cast<int>(g.size());
    if (from < 0 || to < 0 || from >= n || to >= n)
        fail("shortestPath: vertices ", from, " and ", to, " must lie in [0, ", n, ")");
    std::vector<double> dist(g.size(), std::numeric_limits<double>::infinity());
    std::vector<int> prev(g.size(), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist[static_cast<std::size_t>(from)] = 0;
    queue.push({ 0.0, from });
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (v == to)
            break;
        if (d > dist[static_cast<std::size_t>(v)])
            continue;
        for (const auto& [w, length] : g[static_cast<std::size_t>(v)])
            if (d + length < dist[static_cast<std::size_t>(w)]) {
                dist[static_cast<std::size_t>(w)] = d + length;
                prev[static_cast<std::size_t>(w)] = v;
                queue.push({ d + length, w });
            }
    }
    if (from != to && prev[static_cast<std::size_t>(to)] < 0)
        return {};
    std::vector<int> path { to };
    while (path.back() != from)
        path.push_back(prev[static_cast<std::size_t>(path.back())]);
    std::reverse(path.begin(), path.end());
    return path;
}

} // namespace facesketch

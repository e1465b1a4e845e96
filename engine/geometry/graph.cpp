#include "geometry/graph.h"

#include "core/error.h"
#include "geometry/wedges.h"

#include <algorithm>
#include <limits>
#include <numeric>

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

} // namespace facesketch

#include "geometry/wedges.h"

#include <algorithm>

namespace facesketch {

Wedges buildWedges(const Triangles& F, Eigen::Index vertexCount)
{
    Wedges w;
    w.offsets.assign(static_cast<size_t>(vertexCount) + 1, 0);
    for (Eigen::Index t = 0; t < F.rows(); ++t)
        for (int c = 0; c < 3; ++c)
            ++w.offsets[F(t, c) + 1];
    for (size_t v = 0; v < static_cast<size_t>(vertexCount); ++v)
        w.offsets[v + 1] += w.offsets[v];

    w.corners.resize(static_cast<size_t>(F.rows()) * 3);
    std::vector<std::uint32_t> fill(w.offsets.begin(), w.offsets.end() - 1);
    for (Eigen::Index t = 0; t < F.rows(); ++t)
        for (int c = 0; c < 3; ++c) {
            const auto v = F(t, c);
            w.corners[fill[v]++] = { static_cast<std::uint32_t>(F(t, (c + 1) % 3)), static_cast<std::uint32_t>(F(t, (c + 2) % 3)) };
        }
    return w;
}

Neighbours buildNeighbours(const Wedges& wedges)
{
    Neighbours n;
    n.offsets.push_back(0);
    std::vector<std::uint32_t> ring;
    for (size_t v = 0; v + 1 < wedges.offsets.size(); ++v) {
        ring.clear();
        for (std::uint32_t w = wedges.offsets[v]; w < wedges.offsets[v + 1]; ++w)
            ring.insert(ring.end(), wedges.corners[w].begin(), wedges.corners[w].end());
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
        n.vertices.insert(n.vertices.end(), ring.begin(), ring.end());
        n.offsets.push_back(static_cast<std::uint32_t>(n.vertices.size()));
    }
    return n;
}

} // namespace facesketch

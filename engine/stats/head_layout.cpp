#include "stats/head_layout.h"

#include "core/error.h"

#include <algorithm>

namespace facesketch::stats {

void validateHeadLayout(const HeadLayout& layout, Eigen::Index skinVertices, const std::string& where)
{
    const int V = layout.vertexCount;
    if (V <= 0 || layout.skinBegin < 0 || layout.skinBegin + skinVertices > V)
        fail(where, ": head of ", V, " vertices cannot hold ", skinVertices, " skin vertices from ", layout.skinBegin);
    std::vector<int> owner(static_cast<size_t>(V), -1);
    for (Eigen::Index v = 0; v < skinVertices; ++v)
        owner[static_cast<size_t>(layout.skinBegin + v)] = 0;
    for (size_t p = 0; p < layout.parts.size(); ++p) {
        const RigidPart& part = layout.parts[p];
        if (part.mean.rows() != static_cast<Eigen::Index>(part.vertices.size()) || part.anchors.empty())
            fail(where, ": rigid part '", part.name, "' has ", part.vertices.size(), " vertices, ", part.mean.rows(),
                " mean positions and ", part.anchors.size(), " anchors");
        for (int v : part.vertices) {
            if (v < 0 || v >= V)
                fail(where, ": rigid part '", part.name, "' holds vertex ", v, " outside [0, ", V, ")");
            if (owner[static_cast<size_t>(v)] != -1)
                fail(where, ": rigid part '", part.name, "' holds vertex ", v, ", already in the skin or another part");
            owner[static_cast<size_t>(v)] = 1;
        }
        for (int a : part.anchors)
            if (a < 0 || a >= skinVertices)
                fail(where, ": rigid part '", part.name, "' has anchor ", a, " outside the skin [0, ", skinVertices, ")");
    }
    const auto missing = std::find(owner.begin(), owner.end(), -1);
    if (missing != owner.end())
        fail(where, ": head vertex ", missing - owner.begin(), " is neither skin nor in a rigid part");
    if (layout.topology.size() > 0 && (layout.topology.minCoeff() < 0 || layout.topology.maxCoeff() >= V))
        fail(where, ": a head triangle index outside [0, ", V, ")");
}

} // namespace facesketch::stats

#pragma once
// Vertex-to-triangle incidence ("wedges") of a triangle list, in compressed-row form. For
// vertex v, wedges [offsets[v], offsets[v+1]) hold, for each triangle (v, b, c) at v rotated to
// start at v, the pair (b, c) in winding order. The layout GPU kernels gather over: one topology
// serves every mesh of a dataset.

#include "core/mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace facesketch {

struct Wedges {
    std::vector<std::uint32_t> offsets;                ///< #V + 1
    std::vector<std::array<std::uint32_t, 2>> corners; ///< 3 #F, grouped by vertex
};

/// F: #F by 3 triangle indices in [0, vertexCount) (validated by the caller: core/mesh.h).
/// Within a vertex, wedges keep the order of their triangles in F.
Wedges buildWedges(const Triangles& F, Eigen::Index vertexCount);

/// The one-ring of every vertex in compressed-row form: for vertex v, vertices
/// [offsets[v], offsets[v+1]) are the distinct vertices sharing an edge with it, ascending.
struct Neighbours {
    std::vector<std::uint32_t> offsets;  ///< #V + 1
    std::vector<std::uint32_t> vertices; ///< grouped by vertex
};

/// The one-rings of the wedges' vertices (each neighbour once, though most appear in two wedges).
Neighbours buildNeighbours(const Wedges& wedges);

} // namespace facesketch

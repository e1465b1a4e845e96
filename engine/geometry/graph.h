#pragma once
// The vertex connectivity map of thesis 4.8.4: for every vertex i, the path length (in edges,
// "hops") to every vertex j within k connectivity rings of i, found by Dijkstra's algorithm
// limited to that scope (with unit edge weights it visits vertices in order of hop count, i.e.
// a breadth-first search). Vertices share an edge iff they share a triangle (eq. 4.44). Pairs
// further apart than k rings have no entry ("no known connection"), which the HMM's
// transition (sketch/hmm.cpp, eq. 4.48) treats as infeasible or as a floor.
//
// Storage is sparse, compressed-row: about 1 + 3k(k + 1) entries per vertex on a regular
// triangle mesh (61 for k = 4), so 25,000 vertices take about 1.5 M entries instead of an
// n x n matrix. Building is O(#V x entries per vertex); a lookup is a binary search in the row.

#include "core/mesh.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace facesketch {

class RingDistances {
public:
    RingDistances() = default;
    /// F: #F by 3 triangles over `vertexCount` vertices; k >= 0 rings. Throws Error for a
    /// triangle index outside [0, vertexCount) (naming the triangle) or a negative k.
    RingDistances(const Triangles& F, Eigen::Index vertexCount, int k);

    /// Hops from i to j (0 for i == j), or -1 if j is not within k rings of i. Symmetric.
    int hops(std::uint32_t i, std::uint32_t j) const;

    int rings() const { return k_; }
    Eigen::Index vertexCount() const { return static_cast<Eigen::Index>(offsets_.empty() ? 0 : offsets_.size() - 1); }
    /// Entries stored (pairs within k rings, each vertex with itself included).
    std::size_t entries() const { return targets_.size(); }

private:
    int k_ = 0;
    std::vector<std::uint32_t> offsets_; // #V + 1
    std::vector<std::uint32_t> targets_; // ascending within a row
    std::vector<std::uint8_t> hops_;     // beside targets_
};

/// The edge graph of a mesh weighted by edge length: adjacency[a] holds (b, |V_a - V_b|) for
/// every vertex b sharing a triangle edge with a, b ascending. Only vertices below
/// `vertexLimit` take part (an edge with an end at or past it is left out), so a component that
/// comes first in the vertex order (a dataset's skin) can be walked alone.
struct EdgeGraph {
    std::vector<std::vector<std::pair<int, double>>> adjacency; ///< vertexLimit rows, mm
};

/// V: #V by 3 positions (mm); F: #F by 3 triangles with indices in [0, #V); 0 <= vertexLimit <= #V.
EdgeGraph buildEdgeGraph(const Vertices& V, const Triangles& F, Eigen::Index vertexLimit);

/// Dijkstra (1959): the shortest vertex path from `from` to `to` along the graph's edges, both
/// ends included ({from} when they are equal), or empty if `to` cannot be reached. Among paths
/// of equal length the one the priority queue settles first wins, deterministically. Throws
/// Error for a vertex outside the graph.
std::vector<int> shortestPath(const EdgeGraph& graph, int from, int to);

} // namespace facesketch

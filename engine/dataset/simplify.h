#pragma once
// `--vertices N`: a coarser shared topology for a whole dataset. The reference mesh (the
// neutral or the mean face) is simplified once by quadric edge collapse (meshoptimizer's
// meshopt_simplify); collapses only ever remove vertices, so the result is a subset of the
// original vertices. Every sample and pose keeps exactly that subset, in the original order,
// so the simplified set still shares one topology (thesis 3.1) and every vertex keeps its
// meaning across samples.
//
// Labelled vertices survive unchanged: every landmark, MPEG-4 point and contour vertex is
// locked (it can neither move nor be collapsed away). meshoptimizer 0.18 has no per-vertex
// lock, so locking uses its documented treatment of coincident vertices: a position shared by
// three or more vertices is classified "locked". Each labelled vertex gets two unreferenced
// copies at its exact position before simplification; the copies are dropped afterwards.
// simplifyTopology checks that every locked vertex is still present and throws otherwise.
// Because collapses only remove vertices and never flip edges, a contour whose consecutive
// vertices were joined by an edge keeps those edges.

#include "dataset/manifest.h"

#include <filesystem>
#include <vector>

namespace facesketch::dataset {

/// A kept subset of a dataset's vertices and the triangles between them.
struct Simplification {
    std::vector<int> kept; ///< #V' old vertex indices, strictly increasing (new vertex i = old kept[i])
    Triangles topology;    ///< #F' by 3, indices into the kept vertices (new numbering)
};

/// Simplifies `reference` (#V by 3, the manifest's vertex order, any units) with the manifest's
/// topology to about `targetVertices` vertices, locking every landmark, mpeg4 and contour
/// vertex. Vertices that no triangle uses are dropped. Components keep their order; a
/// component that loses all its vertices is dropped (except "skin", which is an error).
/// Throws Error if targetVertices < 4 or the reference does not match the manifest.
Simplification simplifyTopology(const Vertices& reference, const Manifest& manifest, int targetVertices);

/// The manifest of the simplified set: vertexCount, topology, components, landmarks, mpeg4 and
/// contours renumbered; excluded vertices that were removed are dropped. Samples and poses
/// are copied unchanged.
Manifest simplifyManifest(const Manifest& manifest, const Simplification& simplification);

/// The kept rows of V (#V by 3 -> #V' by 3).
Vertices keepVertices(const Vertices& V, const Simplification& simplification);

/// Simplifies a dataset folder into a new one (written atomically, dataset.h writeDataset):
/// the reference is the mean of all samples' neutral meshes. Returns the number of vertices.
int simplifyDataset(const std::filesystem::path& input, const std::filesystem::path& output, int targetVertices);

} // namespace facesketch::dataset

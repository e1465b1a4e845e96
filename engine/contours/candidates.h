#pragma once
// Contour candidates for one view (thesis 4.3, 4.4): for every face of a dataset, the vertices
// on its silhouette, suggestive and labelled contours, with world and screen positions. A stroke
// is later read against this cloud. The GPU builds it (contours/candidates_gpu.h); this file
// defines the tests and holds the double-precision CPU reference.
//
// Per vertex, with v the unit vector towards the camera, n the normal, k_r and D_w k_r the
// radial curvature and its derivative (contours/curvature.h):
// - silhouette (4.3.1): |n . v| < silhouetteThreshold. The thesis used 0.14 at 863 vertices;
//   the band of a smooth surface near its silhouette narrows with the edge length, which goes as
//   1/sqrt(#V), so the default is 0.14 sqrt(863 / #V) (0.053 at 6,000, 0.026 at 25,000).
// - suggestive (4.3.2; DeCarlo et al. 2003): front-facing (n . v > 0), k_r changes sign between
//   the vertex and a neighbour and the vertex is the end nearer zero (|k_r| smaller; ties to the
//   lower index), and a filter that drops zero crossings of weak curvature, one of two
//   (SuggestiveFilter): the vertex's own strength, D_w k_r l^2 > suggestiveThreshold with l the
//   mean edge length (FaceSketch's first filter); or rtsc's, DeCarlo and Rusinkiewicz's reference
//   implementation (rtsc 1.6): tan(theta) D_w k_r l^2 > rtscThreshold at the zero crossing on
//   the edge, its numerator and denominator (RadialCurvature::rtscNumerator, n . v) interpolated
//   linearly there from both ends. rtsc keeps the passing part of a line where its test changes
//   sign inside a triangle; here a vertex is kept when the crossing next to it passes, so the
//   passing part keeps its vertices and a failing end does not drop its neighbour's.
// - labelled (4.3.3): the dataset's contour vertices, unless facing away (n . v <= -silhouetteThreshold).
// Vertices flagged excluded (4.3.3), and vertices without a tangent plane (zero normal), are
// never candidates. A candidate is then kept only inside
// the screen rectangle and within the world sphere given (4.4's culling).

#include "contours/curvature.h"
#include "geometry/camera.h"
#include "shaders/shared.h"

#include <cstdint>
#include <vector>

namespace facesketch {

/// The contours a candidate lies on, as bits (the kernels' CONTOUR_* in shaders/shared.h).
enum ContourType : std::uint32_t {
    ContourSilhouette = CONTOUR_SILHOUETTE,
    ContourSuggestive = CONTOUR_SUGGESTIVE,
    ContourLabelled = CONTOUR_LABELLED,
};

/// Per-vertex flags of a dataset's topology (the kernels' VERTEX_* in shaders/shared.h).
enum VertexFlag : std::uint32_t {
    VertexLabelled = VERTEX_LABELLED, ///< on a manually labelled contour
    VertexExcluded = VERTEX_EXCLUDED, ///< never a candidate
};

/// Which test keeps a suggestive zero crossing (see above).
enum class SuggestiveFilter : std::uint32_t {
    VertexStrength, ///< D_w k_r l^2 at the vertex over suggestiveThreshold
    RtscCrossing,   ///< tan(theta) D_w k_r l^2 at the crossing over rtscThreshold (rtsc 1.6)
};

struct ContourParams {
    double silhouetteThreshold = 0.14; ///< on |n . v|
    double suggestiveThreshold = 0.02; ///< on D_w k_r l^2 (SuggestiveFilter::VertexStrength)
    SuggestiveFilter suggestiveFilter = SuggestiveFilter::VertexStrength;
    double rtscThreshold = 0.01; ///< on tan(theta) D_w k_r l^2 at a crossing (rtsc's sug_thresh, 0.01)
    double featureSize = 1.0;    ///< l: mean edge length, mm
    /// Screen culling rectangle in pixels (x0, y0, x1, y1), inclusive; default: everything.
    double rect[4] = { -1e30, -1e30, 1e30, 1e30 };
    /// World culling sphere (centre xyz, radius) in mm; default: everything.
    double sphere[4] = { 0, 0, 0, 1e30 };
};

/// The default silhouette threshold for a topology of `vertexCount` vertices (see above).
double defaultSilhouetteThreshold(std::int64_t vertexCount);
/// Mean edge length of a mesh (each undirected edge once), mm.
double meanEdgeLength(const Mesh& mesh);

struct Candidate {
    std::uint32_t mesh = 0;       ///< index of the face in the batch
    std::uint32_t vertex = 0;     ///< vertex index in the shared topology
    std::uint32_t types = 0;      ///< ContourType bits
    float world[3] = { 0, 0, 0 }; ///< mm
    float screen[2] = { 0, 0 };   ///< pixels, (0, 0) top-left
    float depth = 0;              ///< [0, 1], smaller is nearer

    bool operator<(const Candidate& o) const { return mesh != o.mesh ? mesh < o.mesh : vertex < o.vertex; }
};

/// CPU reference: the candidates of meshes[m] given its curvature curv[m] (all meshes share the
/// topology F), sorted by (mesh, vertex). `flags` holds #V VertexFlag bits (or is empty).
/// If `nearTies` is given, it receives (mesh, vertex) of each vertex whose classification is
/// within `tieTolerance` (relative) of a threshold, where a float implementation may differ.
std::vector<Candidate> contourCandidates(const std::vector<Mesh>& meshes, const std::vector<Curvature>& curv,
    const std::vector<std::uint32_t>& flags, const Camera& camera, const ContourParams& params,
    std::vector<std::pair<std::uint32_t, std::uint32_t>>* nearTies = nullptr, double tieTolerance = 1e-3);

} // namespace facesketch

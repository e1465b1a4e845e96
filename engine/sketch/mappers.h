#pragma once
// The mappers behind StrokeReader (sketch/mapper.h), and the pieces of mapping other modules
// share (evaluation/contour_eval.cpp maps contour points with the same nearest-candidate rule,
// the same adaptation to the stroke and the same per-vertex averaging as the nearest mapper).
// Each mapper takes a MappingProblem (the stroke's points and their candidate sets) and returns
// the chosen candidate per point and the observations.

#include "contours/candidates.h"
#include "geometry/camera.h"
#include "geometry/graph.h"
#include "geometry/grid_index.h"
#include "sketch/mapper.h"
#include "sketch/reading.h"

#include <Eigen/Core>
#include <vector>

namespace facesketch::sketch {

struct MappingProblem {
    const Camera& camera;
    const std::vector<Eigen::Vector2d>& screen; ///< n densified points, pixels
    const std::vector<Eigen::Vector3d>& world;  ///< the same, projected (sketch/projection.h), mm
    const std::vector<Candidate>& cloud;        ///< the candidates of the stroke's box
    /// Per point, indices into `cloud`, nearest on screen first (sketch/stroke_candidates.h).
    const std::vector<std::vector<int>>& perPoint;
    /// f(g(v)) of eqs. 4.30-4.37: every vertex of the current face (the template) on screen, #V.
    const std::vector<Eigen::Vector2d>& templateScreen;
    /// Every vertex of the template along the view axis (viewAxis()), mm, #V.
    const std::vector<double>& templateDepth;
    const RingDistances& rings; ///< k-ring hop counts of the topology (4.8.4)
    double tau = 1;             ///< pixels (4.8.5.2)
    const MapperParams& params;
    /// #V flags: vertices earlier strokes of a similar view constrain (MapperParams::drawnSigmaTau),
    /// or null.
    const std::vector<char>* drawn = nullptr;
};

struct Mapping {
    std::vector<int> chosen; ///< per point: index into the cloud, or -1
    /// At most one per vertex, in stroke order (of the first point that maps to the vertex).
    std::vector<VertexObservation> observations;
};

Mapping mapNearest(const MappingProblem& problem);
Mapping mapHeuristic(const MappingProblem& problem);
Mapping mapHmm(const MappingProblem& problem);

/// The endpoint metrics of 4.6.1.1 for the candidates of one end of the stroke (points with
/// candidates, in order: `points`; `first` true for the first of them, false for the last):
/// sx = r_x phi_x and sy = r_y phi_y per candidate of that point (eqs. 4.30-4.35), in [0, 1].
/// phi is the candidate's template vertex's proportional position in the box of all that point's
/// candidates' template vertices (4.30, 4.31 divide by the box's extent), flipped by the stroke
/// orientation (4.32, 4.33: the vector from the first to the middle point). r_x and r_y (4.34,
/// 4.35: dx/dy and dy/dx of the stroke's box) are normalised to dx/(dx+dy) and dy/(dx+dy), a
/// linear blend that keeps both terms in [0, 1] where sigma_s = 0.4 (4.45) is meaningful.
struct EndpointTerms {
    std::vector<double> sx, sy;
};
EndpointTerms endpointTerms(const MappingProblem& problem, const std::vector<std::size_t>& points, bool first);

/// 4.6.2's adaptation of a chosen candidate to the stroke: the candidate moved parallel to the
/// view plane until it lies under the stroke point (screen xy of the point, depth of the
/// candidate). Orthographic views compute it as P^T P x + a (a . c), with P the view plane
/// rows, a the view axis, x the point's world position and c the candidate's; perspective
/// views unproject the pixel at the candidate's depth.
Eigen::Vector3d adaptToStroke(
    const Camera& camera, const Eigen::Vector2d& screen, const Eigen::Vector3d& world, const Candidate& candidate);

/// The unit direction across a stroke at its point i (world, in the view plane: the view axis
/// crossed with the stroke's tangent over two points either side), from the stroke's projected
/// points; zero where the stroke has no direction there (one point, or points on one spot).
Eigen::Vector3d acrossStrokeAt(const std::vector<Eigen::Vector3d>& world, std::size_t i, const Eigen::Vector3d& axis);

/// Several observations of one vertex merged into their mean position (in the order given),
/// strokePoint the first one's. Output in ascending vertex order.
std::vector<VertexObservation> averagePerVertex(const std::vector<VertexObservation>& observations);

/// One candidate list with its screen index (GridIndex over the candidates' screen positions).
struct IndexedCandidates {
    const std::vector<Candidate>* candidates = nullptr;
    const GridIndex* index = nullptr;
};
/// The candidate nearest q on screen over several lists: (list, index in it), or (-1, -1) if
/// all are empty. An earlier list wins a tie with a later one.
std::pair<int, int> nearestCandidate(const std::vector<IndexedCandidates>& lists, const Eigen::Vector2d& q);

/// Candidates' screen positions, for building a GridIndex.
std::vector<Eigen::Vector2d> screenPositions(const std::vector<Candidate>& candidates);

} // namespace facesketch::sketch

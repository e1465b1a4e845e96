#pragma once
// The tracking model (thesis 4.6.4, 4.7.3): what the strokes so far say about each vertex of the
// face, and the face the face model infers from it.
//
// Per vertex the model holds either nothing (missing, the thesis' -1) or a set of linear
// constraints A x = b on its position x (mm): three rows for a vertex a stroke pins in 3D, two
// (the view's x and y rows) for one pinned only in a view's image plane, two (across the stroke
// in the view plane, and the view axis) or one (across the stroke) for an across-stroke
// observation (VertexObservation::acrossStroke). After each stroke:
//   1. supersede (beyond the thesis, whose 4.7.3 and 4.10 name the problem): every constraint of
//      an older stroke drawn from a similar view (view directions within `supersedeAngleDeg`)
//      on a vertex the new stroke maps to, or whose current position lies within
//      `supersedeRadius` mm of the line the new stroke drew (its projected points, measured in
//      its view plane), is dropped, so oversketching a feature replaces it instead of averaging
//      two shapes into a corrupt one, while a neighbouring feature drawn beside it stays;
//   2. the new constraints are added; constraints from different views on one vertex combine
//      (4.7.2): their rows are stacked, and the vertex is measured by the least-squares position
//      (in 3D when the rows span 3D, else in the plane they span), each row weighted by how
//      well a stroke measures it (TrackingOptions::planeNoiseMm, depthNoiseMm);
//   3. the face is rebuilt by stats::reconstruct (correlation on or off per stroke, 4.6.4),
//      with noisy rows as noisy measurements; then, beyond the thesis, rows the face misses by
//      far are down-weighted and the face rebuilt again (robustPasses), so a point read onto
//      the wrong vertex, or strokes that disagree, bend the face less than the rows the model
//      can agree with. The passes before the last judge the misses on the joint model's
//      conditional mean at the constrained vertices only (stats::reconstructAt), so they cost
//      O(o q^2) each, not a whole face;
//   4. the exact constraints are projected onto the face space (4.7.3): each one's b becomes A
//      times the rebuilt vertex, so the next stroke starts from a structure the model can
//      express. Noisy rows keep what the stroke measured: projecting them after every stroke
//      would pull them to the prior a little each time, until they said little of the stroke.
// Undo and redo restore the stored state after k strokes, so the state after k strokes is
// bit-identical whether reached directly or by undoing later strokes.

#include "core/mesh.h"
#include "sketch/reading.h"
#include "stats/face_model.h"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace facesketch::sketch {

class MirrorMap;

struct TrackingOptions {
    /// Step 1: older constraints within this distance (mm, in the stroke's view plane) of the
    /// line the stroke drew are superseded; 0 supersedes only the vertices the stroke maps to.
    /// About a high-resolution edge: a redrawn line that lands on the neighbouring vertices
    /// replaces the old one, while the inner and outer lip lines a few mm apart both stay.
    double supersedeRadius = 2.0;
    /// Step 1: only constraints of strokes whose view direction is within this angle (degrees)
    /// of the new stroke's are superseded; those of other views combine with it.
    double supersedeAngleDeg = 30.0;
    /// Step 3: how well a stroke measures a vertex, as standard deviations in mm (0 pins the
    /// vertex exactly, as the thesis does). `planeNoiseMm` for the rows in the stroke's view
    /// plane (across the stroke, or the image position); `depthNoiseMm` for the row along the
    /// view axis, whose value the reader took from a candidate on another face or from the
    /// current face, so it is known far worse than where the line runs on screen. A noisy row
    /// pulls the face by its weight against the model's prior instead of pinning it
    /// (stats::Observations noise variances), and is not replaced by the face in step 4.
    /// 1.5 mm here, with robustK 0.5 and 3 passes (not in the thesis), fitted on the fitting
    /// faces (`eval strokes --faces contour`: 12 contour-role faces, a cloud of the train faces,
    /// synthetic high set, 1 px noise, the HMM with the whole cloud): from 0.551 / 0.572 /
    /// 0.570 / 0.471 of the mean face's error (front / profile / 34 / all views; rows pinned
    /// and projected, no robust pass) to 0.504 / 0.526 / 0.486 / 0.302. Nearby values (1-2 mm,
    /// K 0.35-0.7, 2-4 passes) were within 0.04 of these; docs/sketching.md has the test faces.
    double planeNoiseMm = 1.5;
    double depthNoiseMm = 0.0;
    /// Step 3, robust: after rebuilding, a noisy row the face misses by more than `robustK`
    /// of its standard deviation has its variance scaled up by the miss (Huber's weight), and
    /// the face is rebuilt again, `robustPasses` times. A reading that mapped a stroke point to
    /// the wrong vertex, or two strokes that disagree, then pull by less than the rows the
    /// face model can agree with.
    int robustPasses = 3;
    double robustK = 0.5;
    /// Step 4 on or off (off keeps the stroke's own positions, as 4.6.4 alone). Step 4 moves
    /// only rows without noise (planeNoiseMm 0, and depth rows without depthNoiseMm).
    bool projectOntoFaceSpace = true;
    /// Clean-up of step 3 (the correlation is chosen per stroke).
    bool cleanUp = true;
    /// Correlation of step 3 when a stroke asks for it (Joint or Thesis).
    stats::Correlation correlation = stats::Correlation::Joint;
};

/// One linear constraint block on one vertex: A x = b (rows orthonormal, 1 to 3 of them).
struct VertexConstraint {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    Eigen::Vector3d noise = Eigen::Vector3d::Zero(); ///< variance of each row's measurement, mm^2
    int rows = 0;
    int stroke = 0;                                      ///< 1-based number of the stroke that made it
    Eigen::Vector3d viewAxis = Eigen::Vector3d::UnitZ(); ///< towards the viewer of that stroke
    bool mirrored = false;                               ///< made by the symmetry option
};

/// How one stroke is applied.
struct ApplyOptions {
    bool correlation = true;
    /// Mirror the observations through this map (sketch/symmetry.h) onto the other half,
    /// where the stroke itself did not map; nullptr: no symmetry.
    const MirrorMap* mirror = nullptr;
};

/// The whole tracked state after some strokes.
struct TrackingState {
    std::vector<std::vector<VertexConstraint>> constraints; ///< per vertex (empty: missing)
    Eigen::VectorXd face;                                   ///< 3#V, mm: the rebuilt face
    int strokes = 0;                                        ///< strokes applied
};

class TrackingModel {
public:
    /// Starts at the model's mean face with nothing observed. The model must outlive this.
    explicit TrackingModel(const stats::FaceModel& model, const TrackingOptions& options = {});

    /// Applies one stroke's reading (steps 1-4 above) and forgets any undone strokes. Throws
    /// Error, leaving the state exactly as it was, for a reading with no observations, a vertex
    /// outside the model or observed twice, a non-finite position, or a viewPlane whose rows
    /// are not orthonormal when a viewPlaneOnly observation needs it.
    void apply(const StrokeReading& reading, const ApplyOptions& options = {});

    /// Returns to the state before the last applied stroke; false (and no change) if none.
    bool undo();
    /// Re-applies the last undone stroke's state; false (and no change) if none.
    bool redo();

    const TrackingState& state() const { return history_[current_]; }
    const Eigen::VectorXd& face() const { return state().face; }
    /// The current face as a mesh on the model's topology (#V by 3).
    Mesh faceMesh() const;
    int strokes() const { return state().strokes; }
    /// Vertices with at least one constraint.
    int observedVertices() const;
    /// #V flags: the vertices a constraint of a stroke other than `exceptStroke` holds, whose
    /// view is within TrackingOptions::supersedeAngleDeg of `viewAxis` (towards the viewer) or
    /// has none (3D): what the user already drew as seen from that view, for the reader
    /// (MapperParams::drawnSigmaTau).
    std::vector<char> drawnVertices(const Eigen::Vector3d& viewAxis, int exceptStroke = 0) const;
    /// The measurements step 3 gives the face model (step 2's combination).
    stats::Observations observations() const;

    const stats::FaceModel& model() const { return model_; }
    const TrackingOptions& options() const { return options_; }

private:
    const stats::FaceModel& model_;
    TrackingOptions options_;
    std::vector<TrackingState> history_; ///< history_[k]: the state after k strokes
    size_t current_ = 0;
};

/// The measurement of one vertex from its constraints (step 2): appended to `observations`.
/// Without noise, the least-squares position within the directions the rows span; with noise,
/// the rows weighted by their inverse variances, measured along the principal directions of
/// their information matrix, each with the variance it has there.
void addCombined(stats::Observations& observations, Eigen::Index vertex, const std::vector<VertexConstraint>& constraints);

} // namespace facesketch::sketch

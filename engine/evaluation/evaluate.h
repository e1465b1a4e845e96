#pragma once
// Measuring the face model on held-out faces (`facesketch eval observe`): reconstruct each
// face from some of its own vertices and compare with the whole face, beside the error of
// the mean face.

#include "evaluation/interval.h"
#include "stats/conditional.h"
#include "stats/face_model.h"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace facesketch::evaluation {

struct ObserveOptions {
    /// Fraction of the vertices measured, drawn independently per face (used if region is empty).
    double fraction = 0.15;
    /// If not empty, exactly these vertices are measured on every face (one feature region).
    std::vector<int> region;
    /// Seed of the random draws of measured vertices.
    std::uint64_t seed = 1;
    stats::ReconstructOptions reconstruct;
};

struct ObserveScore {
    /// Per-vertex Euclidean error of the reconstruction, mm: mean over all vertices of all
    /// faces, and the largest.
    double meanError = 0.0;
    double maxError = 0.0;
    /// The same for the model's mean face, the baseline.
    double meanFaceMeanError = 0.0;
    double meanFaceMaxError = 0.0;
    /// Faces scored, and the mean fraction of their vertices that was measured.
    int faces = 0;
    double measuredFraction = 0.0;
    /// Mean reconstruction time per face, ms.
    double millisecondsPerFace = 0.0;
    /// The 95% interval of meanError / meanFaceMeanError over the draw of the faces
    /// (evaluation/interval.h; every face has as many vertices, so the ratio of the means is
    /// the ratio of the per-face sums).
    Interval ratioInterval;
};

/// @param[in] faces  m by 3#V held-out faces, one per row, on the model's topology (mm)
/// Throws Error for a NaN in faces, a column count other than the model's, a fraction
/// outside (0, 1] or a region vertex out of range.
ObserveScore evaluateObserve(const stats::FaceModel& model, const Eigen::MatrixXd& faces, const ObserveOptions& options = {});

} // namespace facesketch::evaluation

#pragma once
// `facesketch eval poses`: how well a pose model (pose/pose_model.h) poses held-out identities
// (issue 13; thesis 5.4, 5.4.1, fig. 5.19 as numbers). For every `test` identity of a posed
// dataset and every pose but neutral:
//   (a) completion: the pose's minimal FPs (pose/minimal_poses.h) are observed, the rest of the FP
//       pose is completed (primary and alternative mixture), and the mesh is rebuilt by the
//       statistical mapping;
//   (b) mapping: the true FP pose is mapped to the mesh by the statistical mapping and by the RBF
//       deformation of the identity's neutral (inverse multiquadric plus affine, thesis 3.2.9).
// The error of a rebuilt pose is the mean over all #V vertices of |rebuilt - true| (mm); the
// baseline is leaving the face neutral (mean |true displacement|), and a record's ratio is its
// mean error over the baseline's on the same (identity, pose) pairs (< 1: better than neutral).
// Part (c), from simulated pose strokes, appends its records to the same list (posing from
// strokes lives above this module).

#include "pose/pose_data.h"
#include "pose/pose_model.h"

#include <string>
#include <vector>

namespace facesketch::evaluation {

/// One row of the results: {"task", "method", "poses", "mean_mm", "ratio"} in JSON.
struct PoseEvalRecord {
    std::string task;   ///< "completion", "mapping" or "neutral"
    std::string method; ///< "mixture", "alternative"; "statistical", "rbf"; "neutral"
    int poses = 0;      ///< poses evaluated (each on every test identity)
    double meanMm = 0.0;
    double ratio = 0.0; ///< meanMm / the neutral baseline's on the same pairs
};

/// The error of one method on one pose, averaged over the test identities.
struct PosePoseError {
    std::string pose;
    std::string task, method;
    double meanMm = 0.0;
    double neutralMm = 0.0;
};

struct PoseEvaluation {
    int identities = 0;
    std::vector<PoseEvalRecord> results;
    std::vector<PosePoseError> perPose;
};

/// Evaluates parts (a) and (b) on the identities of `test` (pose/pose_data.h loadPoseSet with
/// Role::Test). Throws Error if `test` has no identity, another topology, other FPs than the
/// model, or no pose of the minimal table.
PoseEvaluation evaluatePoses(const pose::PoseModel& model, const pose::PoseSet& test, const std::vector<pose::MinimalPose>& minimal);

} // namespace facesketch::evaluation

#pragma once
// The pose model (`facesketch train-poses`): everything posing needs, learnt from the posed
// identities of a dataset (thesis Ch. 5): the feature points, the training FP poses (for the
// per-FP clusters of reading strokes, thesis 5.3), the completion mixtures (5.4) and the
// FP-to-mesh mapping (5.4.1). Stored by pose_file.h.
//
// A pose is applied to a face of the model's topology as face + displacement, so the model
// poses any face of that topology, not only the training identities.

#include "core/mesh.h"
#include "pose/completion.h"
#include "pose/mapping.h"
#include "pose/minimal_poses.h"
#include "pose/pose_data.h"
#include "stats/conditional.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace facesketch::pose {

struct PoseModel {
    /// #V and the triangles of the topology the model was trained on.
    int vertexCount = 0;
    Triangles topology;
    FeaturePoints fps;
    /// P pose names of the training set ("neutral" included).
    std::vector<std::string> poseNames;
    /// 3#V mean of the training identities' neutral meshes (mm): a face to pose when none is given.
    Eigen::VectorXd meanNeutral;
    /// n by 3F FP displacements of every training pose (mm), and each row's index into poseNames.
    /// With a face's neutral FPs added, the FP clusters of thesis fig. 5.4 on that face.
    Eigen::MatrixXd fpTraining;
    std::vector<int> fpTrainingPose;
    /// The minimal table the completion was chosen with (minimal_poses.h).
    std::vector<MinimalPose> minimal;
    CompletionModel completion;
    PoseMapping mapping;

    Eigen::Index fpCount() const { return fps.size(); }
};

struct PoseModelOptions {
    CompletionOptions completion;
    MappingOptions mapping;
};

/// Trains on the identities of `train`; `validation` (poses of other identities, or `train`
/// itself when the dataset has no others) chooses the completion's K (completion.h). Throws
/// Error if the two sets differ in topology, FPs or pose names, or fitting fails.
PoseModel trainPoseModel(
    const PoseSet& train, const PoseSet& validation, const std::vector<MinimalPose>& minimal, const PoseModelOptions& options);

/// Throws Error "<what>: ..." if `face` does not have the model's vertex count and triangles
/// (a model trained on another topology), or holds a NaN or infinity.
void checkFace(const PoseModel& model, const Mesh& face, const std::string& what);

/// Which completion mixture to use (thesis figs. 5.10, 5.11: the interface lets the user switch).
enum class Interpretation { Primary, Alternative };

/// complete() with the model's primary or alternative mixture and observation noise `noiseMm`.
Completion completePose(
    const PoseModel& model, const stats::Observations& observed, Interpretation which = Interpretation::Primary, double noiseMm = 0.0);

/// The face `neutral` (#V by 3, mm) in the pose whose FP displacements are `fp` (3F), by the
/// statistical mapping: neutral + Psi(fp). Throws Error if the sizes do not match the model or
/// either holds a NaN.
Vertices posedFace(const PoseModel& model, const Vertices& neutral, const Eigen::Ref<const Eigen::VectorXd>& fp);

} // namespace facesketch::pose

#include "pose/pose_model.h"

#include "core/error.h"
#include "core/parallel.h"
#include "stats/check.h"

#include <cmath>

namespace facesketch::pose {

PoseModel trainPoseModel(
    const PoseSet& train, const PoseSet& validation, const std::vector<MinimalPose>& minimal, const PoseModelOptions& options)
{
    if (train.identityCount() == 0)
        fail("trainPoseModel: no training identities");
    if (validation.vertexCount != train.vertexCount || validation.topology != train.topology)
        fail("trainPoseModel: the validation poses have another topology than the training poses");
    if (validation.fps.names != train.fps.names || validation.fps.vertices != train.fps.vertices)
        fail("trainPoseModel: the validation poses have other feature points than the training poses");
    if (validation.poseNames != train.poseNames)
        fail("trainPoseModel: the validation poses have other pose names than the training poses");

    PoseModel model;
    model.vertexCount = train.vertexCount;
    model.topology = train.topology;
    model.fps = train.fps;
    model.poseNames = train.poseNames;
    model.meanNeutral = train.neutrals.colwise().mean().transpose();
    model.fpTraining = train.fpDisplacements;
    for (Eigen::Index i = 0; i < train.identityCount(); ++i)
        for (Eigen::Index p = 0; p < train.poseCount(); ++p)
            model.fpTrainingPose.push_back(static_cast<int>(p));
    model.minimal = minimal;
    // The completion and the mapping are independent fits. The mapping (one PPCA over every mesh
    // coordinate) runs beside the completion's candidates, unless one thread was asked for. If
    // both fail, the completion's error is the one reported, as when they ran in turn.
    parallelFor(2, options.completion.threads == 1 ? 1 : 2, [&](int task) {
        if (task == 0)
            model.completion = fitCompletion(train.fpDisplacements, validation, minimal, options.completion);
        else
            model.mapping = fitMapping(train.fpDisplacements, train.meshDisplacements, options.mapping);
    });
    return model;
}

void checkFace(const PoseModel& model, const Mesh& face, const std::string& what)
{
    if (face.vertexCount() != model.vertexCount)
        fail(what, ": ", face.vertexCount(), " vertices, the pose model was trained on a topology of ", model.vertexCount);
    if (face.F.rows() != model.topology.rows() || face.F != model.topology)
        fail(what, ": its triangles differ from the topology the pose model was trained on");
    for (Eigen::Index v = 0; v < face.V.rows(); ++v)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(face.V(v, c)))
                fail(what, ": vertex ", v, " coordinate ", c, " = ", face.V(v, c), " is not finite");
}

Completion completePose(const PoseModel& model, const stats::Observations& observed, Interpretation which, double noiseMm)
{
    return complete(which == Interpretation::Primary ? model.completion.primary : model.completion.alternative, observed, noiseMm);
}

Vertices posedFace(const PoseModel& model, const Vertices& neutral, const Eigen::Ref<const Eigen::VectorXd>& fp)
{
    if (neutral.rows() != model.vertexCount)
        fail("posedFace: a face of ", neutral.rows(), " vertices, the pose model was trained on ", model.vertexCount);
    stats::requireFinite(neutral, "posedFace: face");
    Eigen::VectorXd displacement;
    mapToMesh(model.mapping, fp, displacement);
    Vertices out = neutral;
    asVector(out) += displacement;
    return out;
}

} // namespace facesketch::pose

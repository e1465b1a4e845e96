#include "pose_fixture.h"

#include "core/error.h"
#include "dataset/synth/face_params.h"
#include "dataset/synth/pose_recipes.h"

namespace facesketch::test {

namespace {

PoseWorld build()
{
    PoseWorld w;
    w.topology = dataset::buildFaceTopology(dataset::Resolution::Low);
    const auto& recipes = dataset::poseRecipes();
    pose::PoseSet set;
    set.fps = pose::featurePoints(w.topology.labels, "synthetic topology");
    set.vertexCount = w.topology.labels.vertexCount;
    set.topology = w.topology.labels.topology;
    for (const auto& r : recipes)
        set.poseNames.push_back(r.name);
    const int identities = 8;
    const Eigen::Index P = static_cast<Eigen::Index>(recipes.size());
    set.neutrals.resize(identities, 3 * set.vertexCount);
    set.meshDisplacements.resize(identities * P, 3 * set.vertexCount);
    set.fpDisplacements.resize(identities * P, 3 * set.fps.size());
    for (int i = 0; i < identities; ++i) {
        set.identities.push_back({ "face_" + std::to_string(i), dataset::Role::Train });
        const dataset::FaceParams params = dataset::sampleFaceParams(1, i);
        Vertices rest = dataset::synthesizeFace(w.topology, params);
        set.neutrals.row(i) = asVector(rest).transpose();
        const Eigen::VectorXd restFps = set.fps.gather(rest);
        for (Eigen::Index p = 0; p < P; ++p) {
            Vertices posed = dataset::synthesizeFace(w.topology, params, recipes[static_cast<std::size_t>(p)].actions);
            set.fpDisplacements.row(set.row(i, p)) = (set.fps.gather(posed) - restFps).transpose();
            set.meshDisplacements.row(set.row(i, p)) = (asVector(posed) - asVector(rest)).transpose();
        }
    }
    pose::PoseModelOptions options;
    options.completion.candidates = { 1, 2, 3 };
    options.completion.restarts = 1;
    const std::vector<pose::MinimalPose> minimal
        = { { "anger", { "4.1", "4.3", "4.5" } }, { "smile_open", { "8.4" } }, { "jaw_open", { "8.2" } } };
    w.model = pose::trainPoseModel(set, set, minimal, options);

    const dataset::FaceParams face = dataset::sampleFaceParams(1, 20);
    w.neutral = { dataset::synthesizeFace(w.topology, face), w.topology.labels.topology };
    for (const auto& r : recipes)
        w.poses.push_back({ dataset::synthesizeFace(w.topology, face, r.actions), w.topology.labels.topology });
    w.front = frameMeshView(w.neutral, parseView("front"), 800, 800);
    return w;
}

} // namespace

const Mesh& PoseWorld::pose(const std::string& name) const
{
    for (std::size_t p = 0; p < model.poseNames.size(); ++p)
        if (model.poseNames[p] == name)
            return poses[p];
    fail("no pose ", name);
}

const PoseWorld& poseWorld()
{
    static const PoseWorld world = build();
    return world;
}

sketch::Stroke traceStroke(const Mesh& face, const std::vector<int>& contour, const OrbitView& view)
{
    const Camera camera = orbitCamera(view);
    sketch::Stroke stroke;
    stroke.view = view;
    for (int v : contour) {
        const glm::dvec3 pixel = camera.project({ face.V(v, 0), face.V(v, 1), face.V(v, 2) });
        stroke.points.push_back({ pixel.x, pixel.y, {} });
    }
    return stroke;
}

double meanError(const Vertices& a, const Vertices& b)
{
    return (a - b).rowwise().norm().mean();
}

sketch::PoseAction strokeAction(const sketch::Stroke& stroke)
{
    sketch::PoseAction a;
    a.kind = sketch::PoseActionKind::Stroke;
    a.stroke = stroke;
    return a;
}

sketch::PoseAction keyframeAction(double time)
{
    sketch::PoseAction a;
    a.kind = sketch::PoseActionKind::Keyframe;
    a.time = time;
    return a;
}

sketch::PoseAction moveKeyframeAction(double time, double to)
{
    sketch::PoseAction a = keyframeAction(time);
    a.kind = sketch::PoseActionKind::MoveKeyframe;
    a.to = to;
    return a;
}

sketch::PoseAction deleteKeyframeAction(double time)
{
    sketch::PoseAction a = keyframeAction(time);
    a.kind = sketch::PoseActionKind::DeleteKeyframe;
    return a;
}

sketch::PoseAction clearAction()
{
    sketch::PoseAction a;
    a.kind = sketch::PoseActionKind::Clear;
    return a;
}

} // namespace facesketch::test

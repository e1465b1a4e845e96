#include "pose/pose_file.h"

#include "core/error.h"
#include "stats/model_io.h"

#include <array>
#include <limits>

namespace facesketch::pose {

namespace {

constexpr std::array<char, 8> kMagic = { 'F', 'S', 'K', 'P', 'O', 'S', 'E', '\0' };

void writeNames(stats::PayloadWriter& w, const std::vector<std::string>& names)
{
    w.scalar<std::uint64_t>(names.size());
    for (const std::string& name : names)
        w.text(name);
}

std::vector<std::string> readNames(stats::PayloadReader& r, const char* what)
{
    const auto count = r.scalar<std::uint64_t>(what);
    // Each name takes at least its 8-byte length: a corrupt count fails here, not in reserve().
    std::vector<std::string> names;
    for (std::uint64_t i = 0; i < count; ++i)
        names.push_back(r.text(what));
    return names;
}

} // namespace

void savePoseModel(const PoseModel& model, const std::filesystem::path& path)
{
    stats::PayloadWriter w;
    w.scalar<std::int64_t>(model.vertexCount);
    w.matrix(model.topology);
    writeNames(w, model.fps.names);
    w.indices(model.fps.vertices);
    writeNames(w, model.poseNames);
    w.matrix(model.meanNeutral);
    w.matrix(model.fpTraining);
    w.indices(model.fpTrainingPose);
    w.scalar<std::uint64_t>(model.minimal.size());
    for (const MinimalPose& entry : model.minimal) {
        w.text(entry.pose);
        writeNames(w, entry.fps);
    }
    w.mixture(model.completion.primary);
    w.mixture(model.completion.alternative);
    w.scalar<std::uint64_t>(model.completion.scores.size());
    for (const CompletionScore& s : model.completion.scores) {
        w.scalar<std::int64_t>(s.components);
        w.scalar<std::int64_t>(s.fitted);
        w.scalar<std::int64_t>(s.latentDim);
        w.scalar(s.minimalError);
        w.scalar(s.logLikelihood);
    }
    w.ppca(model.mapping.fp);
    w.ppca(model.mapping.mesh);
    w.mixture(model.mapping.joint);
    stats::writeModelContainer(path, kMagic, kPoseModelVersion, w.bytes());
}

PoseModel loadPoseModel(const std::filesystem::path& path)
{
    const std::string payload = stats::readModelContainer(path, kMagic, kPoseModelVersion, "pose model", "retrain it with train-poses");
    stats::PayloadReader r(payload, 0, payload.size(), path);
    PoseModel model;
    const auto vertices = r.scalar<std::int64_t>("the vertex count");
    if (vertices <= 0 || vertices > std::numeric_limits<int>::max())
        fail(path.string(), ": vertex count ", vertices);
    model.vertexCount = static_cast<int>(vertices);
    const Eigen::MatrixXi triangles = r.matrix<std::int32_t>("the triangles");
    if (triangles.cols() != 3 && triangles.size() != 0)
        fail(path.string(), ": the triangles have ", triangles.cols(), " columns, expected 3");
    model.topology = triangles.size() == 0 ? Triangles(0, 3) : Triangles(triangles);
    model.fps.names = readNames(r, "the feature point names");
    model.fps.vertices = r.indices("the feature point vertices");
    model.poseNames = readNames(r, "the pose names");
    model.meanNeutral = r.vector("the mean neutral face");
    model.fpTraining = r.matrix<double>("the training FP poses");
    model.fpTrainingPose = r.indices("the training poses' names");
    const auto entries = r.scalar<std::uint64_t>("the minimal-pose count");
    for (std::uint64_t i = 0; i < entries; ++i) {
        MinimalPose entry;
        entry.pose = r.text("a minimal pose");
        entry.fps = readNames(r, "a minimal pose's feature points");
        model.minimal.push_back(std::move(entry));
    }
    model.completion.primary = r.mixture("the completion mixture");
    model.completion.alternative = r.mixture("the alternative completion mixture");
    const auto scores = r.scalar<std::uint64_t>("the completion score count");
    for (std::uint64_t i = 0; i < scores; ++i) {
        CompletionScore s;
        s.components = static_cast<int>(r.scalar<std::int64_t>("a completion score"));
        s.fitted = static_cast<int>(r.scalar<std::int64_t>("a completion score"));
        s.latentDim = static_cast<int>(r.scalar<std::int64_t>("a completion score"));
        s.minimalError = r.scalar<double>("a completion score");
        s.logLikelihood = r.scalar<double>("a completion score");
        model.completion.scores.push_back(s);
    }
    model.mapping.fp = r.ppca("the FP PPCA");
    model.mapping.mesh = r.ppca("the mesh PPCA");
    model.mapping.joint = r.mixture("the joint mixture");
    if (!r.done())
        fail(path.string(), ": ", payload.size() - r.at(), " unread bytes at the end of the payload");

    // The checksum guards against corruption, not against a writer bug: check that the parts fit.
    auto inconsistent = [&](const auto&... what) { fail(path.string(), ": inconsistent pose model: ", what...); };
    const Eigen::Index F = model.fps.size();
    const Eigen::Index d = 3 * static_cast<Eigen::Index>(model.vertexCount);
    if (model.topology.size() > 0 && (model.topology.minCoeff() < 0 || model.topology.maxCoeff() >= model.vertexCount))
        inconsistent("a triangle index outside [0, ", model.vertexCount, ")");
    if (static_cast<Eigen::Index>(model.fps.vertices.size()) != F)
        inconsistent(F, " feature point names and ", model.fps.vertices.size(), " vertices");
    if (F < 4)
        inconsistent(F, " feature points, fewer than 4");
    for (int v : model.fps.vertices)
        if (v < 0 || v >= model.vertexCount)
            inconsistent("feature point vertex ", v, " outside [0, ", model.vertexCount, ")");
    if (model.meanNeutral.size() != d)
        inconsistent("a mean neutral of ", model.meanNeutral.size(), " values for ", model.vertexCount, " vertices");
    if (model.fpTraining.cols() != 3 * F || static_cast<Eigen::Index>(model.fpTrainingPose.size()) != model.fpTraining.rows())
        inconsistent("training FP poses of ", model.fpTraining.rows(), " by ", model.fpTraining.cols(), " with ",
            model.fpTrainingPose.size(), " pose indices");
    for (int p : model.fpTrainingPose)
        if (p < 0 || p >= static_cast<int>(model.poseNames.size()))
            inconsistent("training pose index ", p, " outside the ", model.poseNames.size(), " pose names");
    for (const stats::Mppca* m : { &model.completion.primary, &model.completion.alternative })
        if (m->size() == 0 || m->dim() != 3 * F)
            inconsistent("a completion mixture of ", m->size(), " components of dimension ", m->dim(), ", expected ", 3 * F);
    for (const stats::Mppca* m : { &model.completion.primary, &model.completion.alternative })
        for (const stats::Ppca& c : m->components)
            if (c.dim() != 3 * F)
                inconsistent("a completion component of dimension ", c.dim(), ", expected ", 3 * F);
    if (model.mapping.fp.dim() != 3 * F || model.mapping.mesh.dim() != d)
        inconsistent("mapping PPCAs of dimensions ", model.mapping.fp.dim(), " and ", model.mapping.mesh.dim());
    const Eigen::Index q = model.mapping.fp.latentDim() + model.mapping.mesh.latentDim();
    if (model.mapping.joint.size() == 0)
        inconsistent("a joint mixture with no components");
    for (const stats::Ppca& c : model.mapping.joint.components)
        if (c.dim() != q)
            inconsistent("a joint component of dimension ", c.dim(), ", expected ", q);
    prepareMapping(model.mapping);
    return model;
}

} // namespace facesketch::pose

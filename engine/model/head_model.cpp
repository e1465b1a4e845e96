#include "model/head_model.h"

#include "core/error.h"
#include "model/head_assembly.h"

namespace facesketch::model {

namespace {

const dataset::Component& skinOf(const dataset::Manifest& manifest)
{
    const dataset::Component* skin = manifest.component("skin");
    if (!skin)
        fail("the dataset has no \"skin\" component");
    return *skin;
}

} // namespace

Triangles skinTriangles(const dataset::Manifest& manifest)
{
    const dataset::Component& skin = skinOf(manifest);
    const Triangles& T = manifest.topology;
    std::vector<Eigen::Index> keep;
    for (Eigen::Index f = 0; f < T.rows(); ++f)
        if (skin.contains(T(f, 0)) && skin.contains(T(f, 1)) && skin.contains(T(f, 2)))
            keep.push_back(f);
    Triangles out(static_cast<Eigen::Index>(keep.size()), 3);
    for (size_t i = 0; i < keep.size(); ++i)
        out.row(static_cast<Eigen::Index>(i)) = T.row(keep[i]).array() - skin.begin;
    return out;
}

int skinLandmark(const dataset::Manifest& manifest, const std::string& name)
{
    const dataset::Component& skin = skinOf(manifest);
    const auto it = manifest.landmarks.find(name);
    if (it == manifest.landmarks.end())
        fail("the dataset has no landmark \"", name, "\"");
    if (!skin.contains(it->second))
        fail("landmark \"", name, "\" is vertex ", it->second, ", outside the skin [", skin.begin, ", ", skin.end, ")");
    return it->second - skin.begin;
}

stats::FaceModel trainHeadModel(const dataset::Dataset& dataset, const HeadModelOptions& options, const stats::TrainProgress& progress)
{
    const dataset::Manifest& m = dataset.manifest;
    const std::string where = dataset.folder.string();
    if (m.units != "mm")
        fail(where, ": units are ", m.units, "; the face model is trained in mm");
    const dataset::Component& skin = skinOf(m);
    const int nose = skinLandmark(m, "prn");
    if (m.samplesWithRole(dataset::Role::Train).size() < 4)
        fail(where, ": ", m.samplesWithRole(dataset::Role::Train).size(), " train samples, need at least 4");
    if (progress)
        progress("loading faces", 0.0);
    const Eigen::MatrixXd heads = dataset::loadShapes(dataset, dataset::Role::Train);
    const Eigen::MatrixXd faces = heads.middleCols(3 * skin.begin, 3 * skin.size());

    // The skin model reports fractions of its own run: 5% to 99% of the whole.
    stats::TrainProgress inner;
    if (progress)
        inner = [&](const std::string& what, double f) { progress(what, 0.05 + 0.94 * f); };
    stats::FaceModel model = trainFaceModel(faces, skinTriangles(m), nose, options.face, inner);

    const Vertices meanHead = dataset::unflatten(heads.colwise().mean());
    const Vertices meanSkin = meanHead.middleRows(skin.begin, skin.size());
    stats::HeadLayout& head = model.head;
    head.vertexCount = m.vertexCount;
    head.skinBegin = skin.begin;
    head.topology = m.topology;
    std::vector<bool> owned(static_cast<size_t>(m.vertexCount), false);
    for (const dataset::Component& c : m.components) {
        for (int v = c.begin; v < c.end; ++v)
            owned[static_cast<size_t>(v)] = true;
        if (c.name == "skin" || c.size() == 0)
            continue;
        std::vector<int> vertices(static_cast<size_t>(c.size()));
        for (int v = c.begin; v < c.end; ++v)
            vertices[static_cast<size_t>(v - c.begin)] = v;
        head.parts.push_back(makeRigidPart(c.name, vertices, meanSkin, meanHead, options.anchors, options.scale));
    }
    std::vector<int> rest;
    for (int v = 0; v < m.vertexCount; ++v)
        if (!owned[static_cast<size_t>(v)])
            rest.push_back(v);
    if (!rest.empty())
        head.parts.push_back(makeRigidPart("unassigned", rest, meanSkin, meanHead, options.anchors, options.scale));
    stats::validateHeadLayout(head, skin.size(), where);
    if (progress)
        progress("rigid parts placed", 1.0);
    return model;
}

void requireModelFits(const stats::FaceModel& model, const dataset::Manifest& manifest, const std::string& where)
{
    const dataset::Component& skin = skinOf(manifest);
    if (model.vertexCount() != skin.size())
        fail(where, ": the model has ", model.vertexCount(), " skin vertices, the dataset ", skin.size(),
            "; train a model on this dataset's resolution");
    if (model.head.vertexCount != 0 && (model.head.vertexCount != manifest.vertexCount || model.head.skinBegin != skin.begin))
        fail(where, ": the model's head has ", model.head.vertexCount, " vertices with the skin from ", model.head.skinBegin,
            ", the dataset ", manifest.vertexCount, " from ", skin.begin);
}

} // namespace facesketch::model

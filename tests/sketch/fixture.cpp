#include "fixture.h"

#include "dataset/dataset.h"
#include "dataset/synth/synth_dataset.h"
#include "evaluation/contour_eval.h"
#include "model/head_model.h"
#include "test_common.h"

#include <filesystem>
#include <memory>

namespace facesketch::test {

const SketchWorld& sketchWorld(std::uint64_t seed)
{
    static std::map<std::uint64_t, std::unique_ptr<SketchWorld>> worlds;
    std::unique_ptr<SketchWorld>& world = worlds[seed];
    if (world)
        return *world;
    world = std::make_unique<SketchWorld>();
    static TempDir dir;
    dataset::SynthOptions synth;
    synth.identities = 40;
    synth.resolution = dataset::Resolution::Low;
    synth.seed = seed;
    const std::filesystem::path faces = dir / ("faces-" + std::to_string(seed));
    dataset::writeSynthDataset(faces, synth);
    const dataset::Dataset d = dataset::openDataset(faces);
    world->manifest = d.manifest;
    const dataset::Component* skin = d.manifest.component("skin");
    REQUIRE(skin);
    const Triangles skinF = model::skinTriangles(d.manifest);
    std::vector<Mesh> train;
    for (const dataset::Sample& s : d.manifest.samples) {
        const Mesh full = dataset::loadMesh(d, s.file);
        const Mesh m { full.V.middleRows(skin->begin, skin->size()), skinF };
        if (s.role == dataset::Role::Train)
            train.push_back(m);
        else if (s.role == dataset::Role::Contour)
            world->candidateFaces.push_back(m);
        else
            world->testFaces.push_back(m);
    }
    Eigen::MatrixXd shapes(static_cast<Eigen::Index>(train.size()), 3 * skin->size());
    for (std::size_t i = 0; i < train.size(); ++i)
        shapes.row(static_cast<Eigen::Index>(i)) = dataset::flatten(train[i].V);
    stats::FaceModelOptions o;
    o.components = { 1 };
    o.folds = 2;
    world->model = stats::trainFaceModel(shapes, skinF, model::skinLandmark(d.manifest, "prn"), o);
    world->flags = evaluation::skinContourFlags(d.manifest);
    for (const auto& [name, path] : d.manifest.contours) {
        std::vector<int>& out = world->contours[name];
        for (int v : path)
            if (skin->contains(v))
                out.push_back(v - skin->begin);
    }
    world->mean.F = skinF;
    world->mean.V = asVertices(world->model.meanFace);
    return *world;
}

} // namespace facesketch::test

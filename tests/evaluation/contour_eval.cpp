#include "evaluation/contour_eval.h"
#include "core/error.h"
#include "dataset/dataset.h"
#include "dataset/synth/synth_dataset.h"
#include "model/head_model.h"
#include "test_common.h"

#include <iostream>

using namespace facesketch;

TEST_CASE("contour_eval: a held-out face's own contours rebuild it better than the mean face")
{
    test::TempDir dir;
    dataset::SynthOptions synth;
    synth.identities = 60;
    synth.resolution = dataset::Resolution::Low;
    dataset::writeSynthDataset(dir / "faces", synth);
    const dataset::Dataset d = dataset::openDataset(dir / "faces");
    const dataset::Component* skin = d.manifest.component("skin");
    REQUIRE(skin);

    const Triangles skinF = model::skinTriangles(d.manifest);
    std::vector<Mesh> train, candidates;
    evaluation::ContourEvalData data;
    for (const dataset::Sample& s : d.manifest.samples) {
        const Mesh full = dataset::loadMesh(d, s.file);
        const Mesh m { full.V.middleRows(skin->begin, skin->size()), skinF };
        if (s.role == dataset::Role::Test) {
            data.testNames.push_back(s.name);
            data.testFaces.push_back(m);
        } else {
            candidates.push_back(m);
            if (s.role == dataset::Role::Train)
                train.push_back(m);
        }
    }
    Eigen::MatrixXd shapes(static_cast<Eigen::Index>(train.size()), 3 * skin->size());
    for (size_t i = 0; i < train.size(); ++i)
        shapes.row(static_cast<Eigen::Index>(i)) = dataset::flatten(train[i].V);
    stats::FaceModelOptions o;
    o.components = { 1, 2 };
    o.folds = 3;
    const stats::FaceModel model = stats::trainFaceModel(shapes, skinF, model::skinLandmark(d.manifest, "prn"), o);

    data.model = &model;
    data.candidateFaces = candidates;
    data.flags = evaluation::skinContourFlags(d.manifest);

    evaluation::ContourEvalOptions options;
    options.views = { { "front", { 0, 0 } }, { "34", { 45, 0 } } };
    options.imageSize = 512;
    const auto results = evaluation::evaluateContours(test::device(), data, options);
    REQUIRE(results.size() == data.testFaces.size() * 2 * 3);
    for (const auto& r : results) {
        std::cout << r.face << " " << r.view << " " << evaluation::mappingName(r.mapping) << ": " << r.points << " points, "
                  << r.observedVertices << " vertices, mean " << r.meanError << " mm (max " << r.maxError << "), mean face "
                  << r.meanFaceMean << " mm\n";
        INFO(r.face << " " << r.view << " " << evaluation::mappingName(r.mapping));
        REQUIRE(r.points > 20);
        if (r.mapping == evaluation::ContourMapping::KnownVertex && r.view == "front")
            CHECK(r.meanError < 0.5 * r.meanFaceMean);
        else
            CHECK(r.meanError < r.meanFaceMean);
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

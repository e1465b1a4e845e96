#include "evaluation/contour_eval.h"
#include "core/error.h"
#include "dataset/dataset.h"
#include "dataset/synth/synth_dataset.h"
#include "model/head_model.h"
#include "test_common.h"

#include <cmath>
#include <iostream>
#include <map>

using namespace facesketch;

TEST_CASE("contour_eval: held-out faces' own contours rebuild them better than the mean face, on average and with margin")
{
    // The claim is the thesis' (4.5): rebuilt from its contours, a held-out face is nearer the
    // truth than the mean face, on average. 150 identities give 12 held-out faces. Not per
    // face: a face near the mean (mean-face error about 2.6 mm) or one whose candidate mapping
    // strays loses to the mean face now and then (3 of 12 here, up to 1.23 times its mean-face
    // error; docs/realism.md), and a per-face check on 5 faces passed or failed by the draw.
    test::TempDir dir;
    dataset::SynthOptions synth;
    synth.identities = 150;
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
    REQUIRE(data.testFaces.size() >= 10);
    REQUIRE(results.size() == data.testFaces.size() * 2 * 3);
    // Per (view, mapping): summed errors of the rebuilt faces and of the mean face.
    std::map<std::pair<std::string, std::string>, std::pair<double, double>> sums;
    for (const auto& r : results) {
        std::cout << r.face << " " << r.view << " " << evaluation::mappingName(r.mapping) << ": " << r.points << " points, "
                  << r.observedVertices << " vertices, mean " << r.meanError << " mm (max " << r.maxError << "), mean face "
                  << r.meanFaceMean << " mm\n";
        INFO(r.face << " " << r.view << " " << evaluation::mappingName(r.mapping));
        REQUIRE(r.points > 20);
        REQUIRE(std::isfinite(r.meanError));
        // Every face: the known vertices pin it, under half the mean face's error in both views
        // (before: the front only); no candidate mapping loses badly to the mean face.
        if (r.mapping == evaluation::ContourMapping::KnownVertex)
            CHECK(r.meanError < 0.5 * r.meanFaceMean);
        else
            CHECK(r.meanError < 1.5 * r.meanFaceMean);
        auto& [rebuilt, meanFace] = sums[{ r.view, evaluation::mappingName(r.mapping) }];
        rebuilt += r.meanError;
        meanFace += r.meanFaceMean;
    }
    // On average, with margin: on main's generator the candidate mappings give 0.47-0.59 of the
    // mean face's error, the known vertices 0.06-0.08.
    for (const auto& [key, sum] : sums) {
        INFO(key.first << " " << key.second << ": " << sum.first / sum.second << " of the mean face's error");
        CHECK(sum.first < 0.75 * sum.second);
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

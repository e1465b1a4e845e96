#include "sketch_data.h"

#include "core/error.h"
#include "evaluation/contour_eval.h"
#include "model/head_model.h"
#include "sketch/simulate.h"
#include "sketch/symmetry.h"

#include <cstdlib>
#include <sstream>

namespace facesketch::app {

std::vector<Mesh> skinFaces(const dataset::Dataset& ds, dataset::Role role, const Triangles& F, std::vector<std::string>* names)
{
    const Eigen::MatrixXd rows = dataset::loadShapes(ds, role, "skin");
    std::vector<Mesh> out;
    for (Eigen::Index i = 0; i < rows.rows(); ++i)
        out.push_back({ dataset::unflatten(rows.row(i)), F });
    if (names)
        for (const dataset::Sample* s : ds.manifest.samplesWithRole(role))
            names->push_back(s->name);
    return out;
}

SketchData loadSketchData(const std::string& datasetFolder, const stats::FaceModel* model)
{
    SketchData d;
    d.dataset = dataset::openDataset(datasetFolder);
    if (model)
        model::requireModelFits(*model, d.dataset.manifest, datasetFolder);
    const dataset::Component* skin = d.dataset.manifest.component("skin");
    if (!skin)
        fail(datasetFolder, ": the manifest has no skin component");
    d.triangles = model::skinTriangles(d.dataset.manifest);
    d.flags = evaluation::skinContourFlags(d.dataset.manifest);
    d.contours = sketch::skinContours(d.dataset.manifest.contours, skin->begin, skin->end);
    d.landmarks = sketch::skinLandmarks(d.dataset.manifest.landmarks, skin->begin, skin->end);
    d.candidateFaces = skinFaces(d.dataset, dataset::Role::Train, d.triangles, &d.trainNames);
    for (Mesh& face : skinFaces(d.dataset, dataset::Role::Contour, d.triangles, nullptr))
        d.candidateFaces.push_back(std::move(face));
    d.testFaces = skinFaces(d.dataset, dataset::Role::Test, d.triangles, &d.testNames);
    return d;
}

Mesh meanMesh(const stats::FaceModel& model)
{
    Mesh m;
    m.F = model.triangles;
    m.V = dataset::unflatten(model.meanFace.transpose());
    return m;
}

std::vector<std::pair<std::string, ViewAngles>> parseViewList(const std::string& text)
{
    std::vector<std::string> tokens;
    std::string token;
    for (char c : text + ",") {
        if (c == ',' || c == ';') {
            if (!token.empty())
                tokens.push_back(token);
            token.clear();
        } else {
            token += c;
        }
    }
    auto numeric = [](const std::string& s) {
        char* end = nullptr;
        std::strtod(s.c_str(), &end);
        return end && *end == '\0' && !s.empty();
    };
    std::vector<std::pair<std::string, ViewAngles>> views;
    for (size_t i = 0; i < tokens.size(); ++i) {
        std::string name = tokens[i];
        // Two numbers in a row are one AZ,EL view; a lone number ("34") is a view name.
        if (numeric(name) && i + 1 < tokens.size() && numeric(tokens[i + 1]))
            name += "," + tokens[++i];
        views.push_back({ name, parseView(name) });
    }
    if (views.empty())
        fail("--views: no view given");
    return views;
}

void addStrokeStyleOptions(CLI::App* cmd, sketch::SimulateOptions& style)
{
    cmd->add_option("--noise", style.noisePx, "Jitter of the simulated strokes, pixels (standard deviation)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 100.0));
    cmd->add_option("--extreme", style.extreme, "Exaggerate the traced faces away from the mean face by this factor")
        ->capture_default_str()
        ->check(CLI::Range(-10.0, 10.0));
    cmd->add_option("--reversed", style.reversed, "Probability that a stroke is drawn from its contour's end back to its start")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--wander", style.wanderPx, "Smooth random offset of each stroke from its contour, pixels (standard deviation)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 100.0));
    cmd->add_option("--wander-length", style.wanderLengthPx, "Correlation length of that offset along the stroke, pixels")
        ->capture_default_str()
        ->check(CLI::Range(1.0, 10000.0));
}

} // namespace facesketch::app

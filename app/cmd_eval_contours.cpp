// `facesketch eval contours`: the thesis' proof that contours carry a face (4.5.1) on a
// dataset's held-out faces, three ways (evaluation/contour_eval.h), with error renders and the
// curve of thesis figure 4.22 (error against the number of training faces).

#include "commands.h"
#include "sketch_data.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "evaluation/contour_eval.h"
#include "model/head_model.h"
#include "render/colormap.h"
#include "render/renderer.h"
#include "stats/model_file.h"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace facesketch::app {

namespace {

struct EvalContoursCommand {
    std::string model, dataset, output, views = "front;profile;34";
    int size = 1024, renders = 3;
    double suggestive = ContourParams {}.suggestiveThreshold;
    double errorScale = 10.0;
    int refinements = evaluation::ContourEvalOptions {}.refinements;
    int trim = evaluation::ContourEvalOptions {}.trim;
    bool curve = false;
};

std::vector<std::pair<std::string, ViewAngles>> parseViews(const std::string& text)
{
    std::vector<std::pair<std::string, ViewAngles>> views;
    std::stringstream in(text);
    for (std::string name; std::getline(in, name, ';');)
        views.push_back({ name, parseView(name) });
    if (views.empty())
        fail("--views: no view given");
    return views;
}

// Mean over faces of the mean error, largest max error, mean points, per (view, mapping).
void printTable(const std::vector<evaluation::ContourEvalResult>& results)
{
    struct Row {
        double mean = 0, max = 0, meanFace = 0, points = 0;
        int n = 0;
    };
    std::map<std::pair<std::string, int>, Row> rows;
    std::vector<std::string> order;
    for (const auto& r : results) {
        Row& row = rows[{ r.view, static_cast<int>(r.mapping) }];
        if (std::find(order.begin(), order.end(), r.view) == order.end())
            order.push_back(r.view);
        row.mean += r.meanError;
        row.max = std::max(row.max, r.maxError);
        row.meanFace += r.meanFaceMean;
        row.points += r.points;
        ++row.n;
    }
    std::cout << std::fixed << std::setprecision(2) << std::left << std::setw(9) << "view" << std::setw(19) << "mapping" << std::right
              << std::setw(8) << "points" << std::setw(11) << "mean mm" << std::setw(10) << "max mm" << std::setw(16) << "mean face mm"
              << std::setw(8) << "ratio"
              << "\n";
    for (const std::string& view : order)
        for (int mapping = 0; mapping < 3; ++mapping) {
            const Row& row = rows[{ view, mapping }];
            std::cout << std::left << std::setw(9) << view << std::setw(19)
                      << evaluation::mappingName(static_cast<evaluation::ContourMapping>(mapping)) << std::right << std::setw(8)
                      << std::setprecision(0) << row.points / row.n << std::setprecision(2) << std::setw(11) << row.mean / row.n
                      << std::setw(10) << row.max << std::setw(16) << row.meanFace / row.n << std::setw(8) << std::setprecision(3)
                      << row.mean / row.meanFace << std::setprecision(2) << "\n";
        }
}

void writeErrorRenders(const EvalContoursCommand& c, const std::vector<evaluation::ContourEvalResult>& results)
{
    std::filesystem::create_directories(c.output);
    gpu::ScopedDevice deviceOwner;
    gpu::Device& device = *deviceOwner;
    {
        Renderer renderer(device, 512, 512, 4);
        int written = 0;
        std::string lastFace;
        int faces = 0;
        for (const auto& r : results) {
            if (r.face != lastFace) {
                lastFace = r.face;
                ++faces;
            }
            if (faces > c.renders)
                continue;
            std::vector<glm::vec4> colours;
            for (Eigen::Index v = 0; v < r.vertexError.size(); ++v)
                colours.push_back(blueToRed(r.vertexError[v] / c.errorScale));
            renderer.clear();
            MeshStyle style;
            renderer.addMesh(r.reconstruction, style, colours);
            const std::filesystem::path file
                = std::filesystem::path(c.output) / (r.face + "-" + r.view + "-" + evaluation::mappingName(r.mapping) + ".png");
            writePng(file, renderer.render(frameMesh(r.reconstruction, parseView(r.view), 512, 512)));
            ++written;
        }
        std::cout << "wrote " << written << " error renders to " << c.output << " (blue 0 mm to red " << c.errorScale << " mm)\n";
    }
}

void runEvalContours(const EvalContoursCommand& c)
{
    Stopwatch clock;
    const stats::FaceModel m = stats::loadFaceModel(c.model);
    const dataset::Dataset ds = dataset::openDataset(c.dataset);
    model::requireModelFits(m, ds.manifest, c.dataset);
    const Triangles F = model::skinTriangles(ds.manifest);

    evaluation::ContourEvalData data;
    data.model = &m;
    data.flags = evaluation::skinContourFlags(ds.manifest);
    data.candidateFaces = skinFaces(ds, dataset::Role::Train, F, nullptr);
    for (Mesh& face : skinFaces(ds, dataset::Role::Contour, F, nullptr))
        data.candidateFaces.push_back(std::move(face));
    data.testFaces = skinFaces(ds, dataset::Role::Test, F, &data.testNames);
    if (data.testFaces.empty())
        fail(c.dataset, ": no `test` samples to evaluate on");

    evaluation::ContourEvalOptions options;
    options.views = parseViews(c.views);
    options.imageSize = c.size;
    options.suggestiveThreshold = c.suggestive;
    options.refinements = c.refinements;
    options.trim = c.trim;
    gpu::ScopedDevice device;
    const std::vector<evaluation::ContourEvalResult> results = evaluation::evaluateContours(*device, data, options);
    std::cout << "# " << data.testFaces.size() << " test faces, cloud of " << data.candidateFaces.size() << " faces, " << m.vertexCount()
              << " skin vertices, " << c.refinements << " refinements, " << c.trim << " trimming rounds, " << clock.seconds() << " s\n";
    printTable(results);
    if (!c.output.empty())
        writeErrorRenders(c, results);

    if (!c.curve)
        return;
    // Thesis figure 4.22: the same measurement with models trained on the first N train faces.
    const Eigen::MatrixXd train = dataset::loadShapes(ds, dataset::Role::Train, "skin");
    const int prn = model::skinLandmark(ds.manifest, "prn");
    options.views = { options.views.front() };
    std::cout << "# error against the number of training faces, view " << options.views.front().first << "\n";
    for (int n : { 4, 10, 25, 50, 100, 182 }) {
        if (n > train.rows())
            break;
        Stopwatch trainClock;
        stats::FaceModelOptions small; // the defaults, with no more cross-validation folds than faces
        small.folds = std::min(small.folds, n);
        const stats::FaceModel subset = stats::trainFaceModel(train.topRows(n), F, prn, small);
        evaluation::ContourEvalData d = data;
        d.model = &subset;
        const std::vector<evaluation::ContourEvalResult> r = evaluation::evaluateContours(*device, d, options);
        double sums[3] = { 0, 0, 0 }, meanFace = 0;
        for (const auto& x : r) {
            sums[static_cast<int>(x.mapping)] += x.meanError;
            meanFace += x.meanFaceMean;
        }
        const double faces = static_cast<double>(r.size()) / 3.0;
        std::cout << "training_faces " << n << "  known-vertex " << sums[0] / faces << " mm  nearest-candidate " << sums[1] / faces
                  << " mm  2d " << sums[2] / faces << " mm  mean-face " << meanFace / r.size() << " mm  (" << trainClock.seconds() << " s)"
                  << std::endl;
    }
}

} // namespace

void addEvalContoursCommand(CLI::App& eval)
{
    auto c = std::make_shared<EvalContoursCommand>();
    auto* cmd = eval.add_subcommand("contours", "Rebuild held-out faces from their own contour points (thesis 4.5.1); errors in mm");
    cmd->add_option("model", c->model, "Model file from `facesketch train`")->required();
    cmd->add_option("dataset", c->dataset, "The dataset it was trained on (its test faces are scored)")->required();
    cmd->add_option("--views", c->views, "Views separated by ';': front, profile, 34 or AZ,EL")->capture_default_str();
    cmd->add_option("--size", c->size, "Image size in pixels for the screen-space mapping")
        ->capture_default_str()
        ->check(CLI::Range(64, 8192));
    cmd->add_option("--suggestive", c->suggestive, "Suggestive contour threshold")->capture_default_str();
    cmd->add_option("--refinements", c->refinements, "Re-mappings against the reconstruction's own contours (0: the thesis)")
        ->capture_default_str()
        ->check(CLI::Range(0, 20));
    cmd->add_option("--trim", c->trim, "Outlier-trimming rounds after each solve (0: none, as the thesis)")
        ->capture_default_str()
        ->check(CLI::Range(0, 20));
    cmd->add_option("-o,--output", c->output, "Folder for colour-coded error renders (blue to red)");
    cmd->add_option("--renders", c->renders, "Test faces to render")->capture_default_str();
    cmd->add_option("--error-scale", c->errorScale, "Error in mm drawn red")->capture_default_str();
    cmd->add_flag("--curve", c->curve, "Also the error against the number of training faces (4 ... 182; trains 6 models)");
    cmd->callback([c] { runEvalContours(*c); });
}

} // namespace facesketch::app

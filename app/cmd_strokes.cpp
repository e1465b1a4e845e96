// `facesketch strokes simulate`: a session file of simulated strokes tracing one face of a
// dataset in one view (sketch/simulate.h), to replay with `facesketch sketch`.

#include "commands.h"
#include "sketch_data.h"

#include "core/error.h"
#include "sketch/refine.h"
#include "sketch/session.h"
#include "sketch/simulate.h"

#include <filesystem>
#include <iostream>

namespace facesketch::app {

namespace {

struct SimulateCommand {
    std::string dataset, sample, view = "front", output, model, mapper = "hmm";
    sketch::SimulateOptions style; ///< how the hand draws (addStrokeStyleOptions)
    int size = 1024;
    std::uint64_t seed = 1;
    bool symmetry = false;
};

void runSimulate(const SimulateCommand& c)
{
    namespace fs = std::filesystem;
    const ViewAngles angles = parseView(c.view);
    if (!c.model.empty() && !fs::is_regular_file(c.model))
        fail("--model: no model file at ", c.model);
    const SketchData d = loadSketchData(c.dataset, nullptr);
    const dataset::Dataset& ds = d.dataset;
    const dataset::Sample* sample = nullptr;
    for (const dataset::Sample& s : ds.manifest.samples)
        if (s.name == c.sample)
            sample = &s;
    if (!sample)
        fail(c.dataset, ": no sample named '", c.sample, "'");
    const dataset::Component& skin = *ds.manifest.component("skin");
    const Mesh whole = dataset::loadMesh(ds, sample->file);
    Mesh face;
    face.V = whole.V.middleRows(skin.begin, skin.size());
    face.F = d.triangles;
    // The face a user starts from: the mean of the training faces.
    Mesh mean;
    mean.F = d.triangles;
    mean.V = Vertices::Zero(skin.size(), 3);
    for (const Mesh& m : std::vector<Mesh>(d.candidateFaces.begin(), d.candidateFaces.begin() + static_cast<long>(d.trainNames.size())))
        mean.V += m.V;
    if (d.trainNames.empty())
        fail(c.dataset, ": no `train` samples to take the mean face from");
    mean.V /= static_cast<double>(d.trainNames.size());

    sketch::SimulateOptions o = c.style;
    o.angles = angles;
    o.imageSize = c.size;
    o.seed = c.seed;
    const sketch::Simulation sim = sketch::simulateStrokes(face, mean, d.contours, d.flags, o);
    if (sim.strokes.empty())
        fail("no feature of ", c.sample, " is visible from ", c.view);

    // Paths in a session are relative to the session file's folder.
    const fs::path folder = fs::absolute(c.output).parent_path();
    const fs::path model
        = c.model.empty() ? fs::path(fs::absolute(c.dataset).lexically_normal().string() + ".model") : fs::absolute(c.model);
    sketch::Session session;
    session.model = model.lexically_relative(folder);
    session.dataset = fs::absolute(c.dataset).lexically_normal().lexically_relative(folder);
    if (session.model.empty())
        session.model = model;
    if (session.dataset.empty())
        session.dataset = fs::absolute(c.dataset);
    std::map<std::string, int> perFeature;
    size_t points = 0;
    for (const sketch::SimulatedStroke& s : sim.strokes) {
        sketch::StrokeAction a;
        a.stroke = s.stroke;
        a.reading.mapper = c.mapper;
        a.reading.symmetry = c.symmetry;
        a.reading.refinePasses = sketch::RefineOptions {}.passes;
        a.reading.refineAnchorRings = sketch::RefineOptions {}.anchorRings;
        a.reading.mapperParams = sketch::mapperParamValues(sketch::MapperParams {});
        session.actions.push_back(std::move(a));
        ++perFeature[s.feature];
        points += s.stroke.points.size();
    }
    sketch::saveSession(c.output, session);
    std::cout << "wrote " << c.output << ": " << session.actions.size() << " strokes, " << points << " points, view " << c.view << " ("
              << angles.azimuthDeg << ", " << angles.elevationDeg << "), noise " << c.style.noisePx << " px, extreme " << c.style.extreme
              << "\n";
    for (const auto& [feature, n] : perFeature)
        std::cout << "  " << feature << ": " << n << " strokes\n";
}

} // namespace

void addStrokesCommand(CLI::App& root)
{
    auto* strokes = root.add_subcommand("strokes", "Stroke files: simulate a user tracing a face");
    strokes->require_subcommand(1);
    auto c = std::make_shared<SimulateCommand>();
    auto* cmd = strokes->add_subcommand("simulate", "Write a session of strokes tracing one face's contours and silhouette in a view");
    cmd->footer("Traces the sample's labelled contours (where they face the camera) and its longest silhouettes as a user\n"
                "would: a few overlapping strokes per feature, partial or overshooting ends, uneven spacing, jitter. The view\n"
                "frames the dataset's mean face. The session (docs/session-format.md) replays with `facesketch sketch`.");
    cmd->add_option("dataset", c->dataset, "Dataset folder")->required();
    cmd->add_option("--sample", c->sample, "Name of the sample to trace")->required();
    cmd->add_option("--view", c->view, "front, profile, 34 or AZ,EL")->capture_default_str();
    cmd->add_option("-o,--output", c->output, "Session file to write")->required();
    addStrokeStyleOptions(cmd, c->style);
    cmd->add_option("--size", c->size, "Viewport size, pixels")->capture_default_str()->check(CLI::Range(64, 8192));
    cmd->add_option("--seed", c->seed, "Seed")->capture_default_str();
    cmd->add_option("--model", c->model, "Model file the session names (default: DATASET.model)");
    cmd->add_option("--mapper", c->mapper, "Mapper each stroke asks for")
        ->check(CLI::IsMember({ "nearest", "heuristic", "hmm", "simple" }))
        ->capture_default_str();
    cmd->add_flag("--symmetry", c->symmetry, "Strokes ask for symmetry");
    cmd->callback([c] { runSimulate(*c); });
}

} // namespace facesketch::app

// `facesketch eval strokes`: every held-out face sketched with its own simulated strokes onto
// the mean face, from each view and from all views together, with each mapper
// (evaluation/stroke_eval.h); a table, a JSON file of the records and optional error renders.

#include "commands.h"
#include "sketch_data.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "evaluation/stroke_eval.h"
#include "render/colormap.h"
#include "render/renderer.h"
#include "stats/model_file.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

namespace facesketch::app {

namespace {

struct EvalStrokesCommand {
    std::string model, dataset, json, perStroke, output, views = "front,profile,34", mappers = "nearest,heuristic,hmm,simple";
    double errorScale = 10.0;
    sketch::SimulateOptions style; ///< how the simulated hand draws (addStrokeStyleOptions)
    int size = 1024, renders = 2, maxFaces = 0, similarFaces = sketch::MapperParams {}.similarFaces, rereads = -1;
    int refine = sketch::RefineOptions {}.passes;
    int refineAnchor = sketch::RefineOptions {}.anchorRings;
    std::string refineMapper = "simple";
    std::uint64_t seed = 1;
    bool noCorrelation = false, quiet = false, noProject = false, ownContours = false, thesisObservations = false;
    std::string oracle = "none", faces = "test";
    double supersedeRadius = sketch::TrackingOptions {}.supersedeRadius;
    double planeNoise = sketch::TrackingOptions {}.planeNoiseMm, depthNoise = sketch::TrackingOptions {}.depthNoiseMm;
    int robustPasses = sketch::TrackingOptions {}.robustPasses;
    double robustK = sketch::TrackingOptions {}.robustK;
    std::vector<std::string> mapperParams;
};

std::vector<sketch::MapperKind> parseMappers(const std::string& text)
{
    std::vector<sketch::MapperKind> out;
    std::stringstream in(text);
    for (std::string name; std::getline(in, name, ',');)
        if (!name.empty())
            out.push_back(sketch::parseMapper(name));
    if (out.empty())
        fail("--mappers: no mapper given");
    return out;
}

void printRecords(const std::vector<evaluation::StrokeEvalRecord>& records)
{
    std::cout << std::fixed << std::left << std::setw(9) << "view" << std::setw(11) << "mapper" << std::right << std::setw(7) << "faces"
              << std::setw(9) << "strokes" << std::setw(8) << "unread" << std::setw(10) << "observed" << std::setw(10) << "mean mm"
              << std::setw(14) << "mean face mm" << std::setw(8) << "ratio" << std::setw(13) << "95% interval" << std::setw(10) << "read ms"
              << std::setw(10) << "apply ms" << std::setw(10) << "plane mm" << std::setw(10) << "depth mm" << std::setw(10) << "across mm"
              << std::setw(8) << "<=1mm" << std::setw(8) << "<=3mm" << std::setw(9) << "misread"
              << "\n";
    for (const auto& r : records)
        std::cout << std::left << std::setw(9) << r.view << std::setw(11) << r.mapper << std::right << std::setw(7) << r.faces
                  << std::setw(9) << r.strokes << std::setw(8) << r.unread + r.failed << std::setw(10) << std::setprecision(0)
                  << r.observedVertices << std::setprecision(2) << std::setw(10) << r.meanMm << std::setw(14) << r.meanFaceMm
                  << std::setprecision(3) << std::setw(8) << r.ratio << std::setw(7) << r.ratioInterval.low << "-" << std::left
                  << std::setw(5) << r.ratioInterval.high << std::right << std::setprecision(1) << std::setw(10) << r.readMs
                  << std::setw(10) << r.applyMs << std::setprecision(2) << std::setw(10) << r.planeMm << std::setw(10) << r.depthMm
                  << std::setw(10) << r.acrossMm << std::setw(8) << r.within1Mm << std::setw(8) << r.within3Mm << std::setprecision(3)
                  << std::setw(9) << r.misread << "\n";
    // The mappers against nearest, paired on the same faces (issue 12's bar is a comparison):
    // far narrower than the difference of two ratio intervals above.
    bool header = false;
    for (const auto& r : records) {
        if (!r.versusNearest)
            continue;
        const evaluation::PairedDifference& p = *r.versusNearest;
        if (!header)
            std::cout << "# against " << p.baseline << " on the same faces: ratio difference (95% interval), faces rebuilt better\n";
        header = true;
        std::cout << std::left << std::setw(9) << r.view << std::setw(11) << r.mapper << std::right << std::showpos << std::setprecision(3)
                  << std::setw(8) << p.difference << "  (" << p.interval.low << " to " << p.interval.high << ")" << std::noshowpos
                  << "  better on " << p.betterFaces << " of " << r.faces << "\n";
    }
}

// Which features each mapper misreads (--per-stroke): the diagnosis behind docs/sketching.md's
// per-feature figures.
void printFeatureReadings(const std::vector<evaluation::FeatureReadings>& rows)
{
    std::cout << "# per feature: strokes drawn, read, misread (median across-stroke error over " << evaluation::kMisreadMm
              << " mm), mean median across-stroke error\n";
    std::cout << std::left << std::setw(9) << "view" << std::setw(22) << "feature" << std::setw(11) << "mapper" << std::right
              << std::setw(9) << "strokes" << std::setw(7) << "read" << std::setw(9) << "misread" << std::setw(11) << "across mm"
              << "  misread as\n";
    for (const auto& r : rows) {
        std::cout << std::left << std::setw(9) << r.view << std::setw(22) << r.feature << std::setw(11) << r.mapper << std::right
                  << std::setw(9) << r.strokes << std::setw(7) << r.read << std::setw(9) << r.misread << std::fixed << std::setprecision(2)
                  << std::setw(11) << r.acrossMm << " ";
        // The lines the misread strokes were read as, most often first.
        std::vector<std::pair<int, std::string>> as;
        for (const auto& [name, count] : r.misreadAs)
            as.emplace_back(-count, name);
        std::sort(as.begin(), as.end());
        for (const auto& [count, name] : as)
            std::cout << " " << name << " " << -count;
        std::cout << "\n";
    }
}

void writePerStroke(const EvalStrokesCommand& c, const std::vector<evaluation::StrokeEvalStroke>& strokes)
{
    nlohmann::json list = nlohmann::json::array();
    for (const auto& s : strokes) {
        list.push_back({ { "face", s.face }, { "view", s.view }, { "mapper", s.mapper }, { "feature", s.feature }, { "read_as", s.readAs },
            { "index", s.index }, { "points", s.points }, { "outcome", evaluation::strokeOutcomeName(s.outcome) },
            { "observations", s.observations }, { "plane_mm", s.planeMm }, { "depth_mm", s.depthMm }, { "misread", s.misread },
            { "read_ms", s.readMs } });
        list.back()["across_mm"] = s.acrossMm ? nlohmann::json(*s.acrossMm) : nlohmann::json(nullptr);
    }
    const nlohmann::json doc { { "model", c.model }, { "dataset", c.dataset }, { "faces", c.faces }, { "noise_px", c.style.noisePx },
        { "extreme", c.style.extreme }, { "seed", c.seed }, { "misread_mm", evaluation::kMisreadMm }, { "strokes", list } };
    writeFileAtomically(c.perStroke, [&](std::ostream& out) { out << doc.dump(1) << "\n"; });
    std::cout << "wrote " << strokes.size() << " stroke readings to " << c.perStroke << "\n";
}

void runEvalStrokes(const EvalStrokesCommand& c)
{
    Stopwatch clock;
    const stats::FaceModel m = stats::loadFaceModel(c.model);
    SketchData d = loadSketchData(c.dataset, &m);
    if (c.faces == "contour") {
        // Fitting parameters: held-out faces that are not the test faces, and not in the
        // cloud, so that no face offers its own contours as candidates.
        d.candidateFaces.resize(d.trainNames.size());
        d.testNames.clear();
        d.testFaces = skinFaces(d.dataset, dataset::Role::Contour, d.triangles, &d.testNames);
    } else if (c.faces != "test") {
        fail("--faces: '", c.faces, "' is neither test nor contour");
    }
    if (d.testFaces.empty())
        fail(c.dataset, ": no `", c.faces, "` samples to evaluate on");
    if (c.maxFaces > 0 && static_cast<int>(d.testFaces.size()) > c.maxFaces) {
        d.testFaces.resize(static_cast<size_t>(c.maxFaces));
        d.testNames.resize(static_cast<size_t>(c.maxFaces));
    }

    evaluation::StrokeEvalData data;
    data.model = &m;
    data.flags = d.flags;
    data.candidateFaces = std::move(d.candidateFaces);
    data.contours = d.contours;
    data.testNames = d.testNames;
    data.testFaces = d.testFaces;

    evaluation::StrokeEvalOptions o;
    o.views = parseViewList(c.views);
    o.mappers = parseMappers(c.mappers);
    o.simulate = c.style;
    o.simulate.imageSize = c.size;
    o.simulate.seed = c.seed;
    o.correlation = !c.noCorrelation;
    o.tracking.supersedeRadius = c.supersedeRadius;
    o.tracking.planeNoiseMm = c.planeNoise;
    o.tracking.depthNoiseMm = c.depthNoise;
    o.tracking.robustPasses = c.robustPasses;
    o.tracking.robustK = c.robustK;
    o.tracking.projectOntoFaceSpace = !c.noProject;
    if (c.thesisObservations)
        o.params = sketch::MapperParams::thesis();
    o.params.ownContours = c.ownContours;
    o.params.similarFaces = c.similarFaces;
    for (const std::string& assignment : c.mapperParams)
        sketch::setMapperParam(o.params, assignment);
    o.refine.passes = c.refine;
    o.refine.mapper = c.refineMapper == "same" ? std::nullopt : std::optional(sketch::parseMapper(c.refineMapper));
    o.refine.anchorRings = c.refineAnchor;
    if (c.rereads >= 0) {
        // The older spelling: passes of the first reading's own mapper.
        o.refine.passes = c.rereads;
        o.refine.mapper.reset();
    }
    o.oracle = evaluation::parseStrokeOracle(c.oracle);
    o.keepFaces = c.output.empty() ? 0 : c.renders;
    o.keepStrokes = !c.perStroke.empty();
    if (!c.quiet)
        o.progress = [](const std::string& line) { std::cout << "# " << line << std::endl; };

    gpu::ScopedDevice device;
    const evaluation::StrokeEvalResult result = evaluation::evaluateStrokes(*device, data, o);
    std::cout << "# " << data.testFaces.size() << " test faces of " << c.dataset << ", cloud of " << data.candidateFaces.size()
              << " faces, " << m.vertexCount() << " skin vertices, noise " << c.style.noisePx << " px, extreme " << c.style.extreme
              << ", reversed " << c.style.reversed << ", wander " << c.style.wanderPx << " px over " << c.style.wanderLengthPx << " px, "
              << clock.seconds() << " s\n";
    printRecords(result.records);
    for (const std::string& note : result.notes)
        std::cout << "# refused: " << note << "\n";
    if (o.keepStrokes) {
        printFeatureReadings(evaluation::readingsByFeature(result.strokes));
        writePerStroke(c, result.strokes);
    }

    if (!c.json.empty()) {
        nlohmann::json records = nlohmann::json::array();
        for (const auto& r : result.records) {
            records.push_back({ { "view", r.view }, { "mapper", r.mapper }, { "noise_px", r.noisePx }, { "faces", r.faces },
                { "mean_mm", r.meanMm }, { "ratio", r.ratio }, { "ratio_low", r.ratioInterval.low }, { "ratio_high", r.ratioInterval.high },
                { "extreme", r.extreme }, { "mean_face_mm", r.meanFaceMm }, { "strokes", r.strokes }, { "unread", r.unread },
                { "failed", r.failed }, { "observed_vertices", r.observedVertices }, { "read_ms", r.readMs }, { "apply_ms", r.applyMs },
                { "plane_mm", r.planeMm }, { "depth_mm", r.depthMm }, { "across_mm", r.acrossMm }, { "within_1mm", r.within1Mm },
                { "within_3mm", r.within3Mm }, { "misread_strokes", r.misread } });
            if (r.versusNearest) {
                const evaluation::PairedDifference& p = *r.versusNearest;
                records.back()["versus"] = { { "mapper", p.baseline }, { "ratio_difference", p.difference },
                    { "difference_low", p.interval.low }, { "difference_high", p.interval.high }, { "better_faces", p.betterFaces } };
            }
        }
        const nlohmann::json doc { { "model", c.model }, { "dataset", c.dataset }, { "vertices", m.vertexCount() },
            { "image_size", c.size }, { "seed", c.seed }, { "reversed", c.style.reversed }, { "wander_px", c.style.wanderPx },
            { "wander_length_px", c.style.wanderLengthPx }, { "correlation", !c.noCorrelation },
            { "supersede_radius_mm", c.supersedeRadius }, { "plane_noise_mm", c.planeNoise }, { "depth_noise_mm", c.depthNoise },
            { "robust_passes", c.robustPasses }, { "robust_k", c.robustK }, { "project_onto_face_space", !c.noProject },
            { "view_plane_only", o.params.viewPlaneOnly }, { "own_contours", o.params.ownContours },
            { "across_stroke", o.params.acrossStrokeOnly }, { "similar_faces", o.params.similarFaces },
            { "refine_passes", o.refine.passes }, { "refine_mapper", o.refine.mapper ? sketch::mapperName(*o.refine.mapper) : "same" },
            { "refine_anchor_rings", o.refine.anchorRings }, { "mapper_params", c.mapperParams }, { "oracle", c.oracle },
            { "faces", c.faces }, { "results", records } };
        writeFileAtomically(c.json, [&](std::ostream& out) { out << doc.dump(1) << "\n"; });
        std::cout << "wrote " << c.json << "\n";
    }

    if (!c.output.empty()) {
        std::filesystem::create_directories(c.output);
        Renderer renderer(*device, 512, 512, 4);
        for (const auto& k : result.kept) {
            std::vector<glm::vec4> colours;
            for (Eigen::Index v = 0; v < k.vertexError.size(); ++v)
                colours.push_back(blueToRed(k.vertexError[v] / c.errorScale));
            renderer.clear();
            renderer.addMesh(k.reconstruction, MeshStyle {}, colours);
            const std::string view = k.view == "all" ? "34" : k.view;
            writePng(std::filesystem::path(c.output) / (k.face + "-" + k.view + "-" + k.mapper + ".png"),
                renderer.render(frameMesh(k.reconstruction, parseView(view), 512, 512)));
        }
        std::cout << "wrote " << result.kept.size() << " error renders to " << c.output << " (blue 0 mm to red " << c.errorScale
                  << " mm)\n";
    }
}

} // namespace

void addEvalStrokesCommand(CLI::App& eval)
{
    auto c = std::make_shared<EvalStrokesCommand>();
    auto* cmd = eval.add_subcommand("strokes", "Sketch held-out faces with their own simulated strokes; errors in mm per view and mapper");
    cmd->footer("For every `test` face of DATASET: simulated strokes of its own contours and silhouette (as `facesketch strokes\n"
                "simulate`) are read by each mapper and applied to the tracking model from the mean face, from each view\n"
                "alone and from all views together (view \"all\"). Prints the mean per-vertex error in mm and its ratio to\n"
                "the mean face's error, with the ratio's 95% interval over the draw of the faces (a bootstrap); --json\n"
                "writes one record per (view, mapper): {\"view\", \"mapper\", \"noise_px\", \"faces\", \"mean_mm\", \"ratio\",\n"
                "\"ratio_low\", \"ratio_high\", ...} under \"results\". With nearest among the mappers, every other mapper is\n"
                "also compared with it face by face: the difference of the ratios with its 95% interval (the faces resampled\n"
                "in pairs) and the faces rebuilt better; JSON \"versus\": {\"mapper\", \"ratio_difference\", \"difference_low\",\n"
                "\"difference_high\", \"better_faces\"}.");
    cmd->add_option("model", c->model, "Model file from `facesketch train`")->required();
    cmd->add_option("dataset", c->dataset, "The dataset it was trained on (its test faces are sketched)")->required();
    cmd->add_option("--views", c->views, "Views separated by ',' or ';': front, profile, 34 or AZ,EL")->capture_default_str();
    cmd->add_option("--mappers", c->mappers, "Mappers separated by ','")->capture_default_str();
    addStrokeStyleOptions(cmd, c->style);
    cmd->add_option("--size", c->size, "Viewport size of the strokes, pixels")->capture_default_str()->check(CLI::Range(64, 8192));
    cmd->add_option("--seed", c->seed, "Seed of the simulated strokes")->capture_default_str();
    cmd->add_option("--faces", c->faces,
           "Which faces are sketched: test, or contour (to fit parameters on: the contour-role faces, with a cloud of the train "
           "faces only)")
        ->capture_default_str();
    cmd->add_option("--max-faces", c->maxFaces, "Sketch only the first N test faces (0: all)")->check(CLI::Range(0, 100000));
    cmd->add_flag("--no-correlation", c->noCorrelation, "Unmeasured segments keep the mean face");
    cmd->add_option("--supersede-radius", c->supersedeRadius, "Tracking: older constraints this near a new stroke's line are replaced, mm")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1000.0));
    cmd->add_option("--plane-noise", c->planeNoise, "Tracking: how well a stroke places a vertex in its view plane, mm (0: exactly)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 100.0));
    cmd->add_option("--depth-noise", c->depthNoise, "Tracking: how well a stroke's reading gives a vertex's depth, mm (0: exactly)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1000.0));
    cmd->add_option("--robust-passes", c->robustPasses, "Tracking: rebuilds that reweight rows the face misses (Huber)")
        ->capture_default_str()
        ->check(CLI::Range(0, 10));
    cmd->add_option("--robust-k", c->robustK, "Tracking: misses beyond this many standard deviations are reweighted")
        ->capture_default_str()
        ->check(CLI::Range(0.1, 100.0));
    cmd->add_flag("--no-project", c->noProject, "Tracking: keep the strokes' own positions instead of projecting them onto the face space");
    cmd->add_flag("--thesis-observations", c->thesisObservations,
        "The thesis' mapper parameters (MapperParams::thesis()): observations pin the stroke point in 3D (4.6.2) instead of the offset "
        "across the stroke in its view plane, sigma_d = 2 tau, 48 candidates per point");
    cmd->add_option("--similar-faces", c->similarFaces, "Candidates only of this many training faces nearest the current face (0: all)")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000));
    auto* refine = cmd->add_option("--refine", c->refine,
                          "Refinement passes: read each stroke again this many times against the face its reading rebuilt, each "
                          "reading replacing the previous one (sketch/refine.h; 0: the first reading alone)")
                       ->capture_default_str()
                       ->check(CLI::Range(0, 16));
    auto* refineMapper = cmd->add_option("--refine-mapper", c->refineMapper,
                                "Mapper of the refinement passes: nearest, heuristic, hmm, simple, or same (the first reading's)")
                             ->capture_default_str()
                             ->check(CLI::IsMember({ "nearest", "heuristic", "hmm", "simple", "same" }));
    cmd->add_option("--refine-anchor", c->refineAnchor,
           "The passes read the face's own lines only within this many rings of the first reading's vertices (silhouettes "
           "anywhere; -1: all)")
        ->capture_default_str()
        ->check(CLI::Range(-1, 4));
    cmd->add_option("--rereads", c->rereads, "The older spelling of --refine N --refine-mapper same")
        ->check(CLI::Range(0, 16))
        ->excludes(refine)
        ->excludes(refineMapper);
    cmd->add_option("--mapper-param", c->mapperParams,
        "Set one mapper parameter, NAME=VALUE (repeatable; names as in sketch/mapper_params.h MapperParams, e.g. sigmaDTau=2, "
        "useSkeleton=0)");
    cmd->add_flag("--own-contours", c->ownContours, "The current face's own contours join the candidate cloud");
    cmd->add_option("--oracle", c->oracle,
           "Diagnosis: give the tracking model the mapped vertices at the true depth (true-depth) or true position (true-position), "
           "or instead every vertex the stroke traces, across its true contour (true-curve) or at its true image (true-image)")
        ->capture_default_str();
    cmd->add_option("--json", c->json, "Write the records to this JSON file");
    cmd->add_option("--per-stroke", c->perStroke,
        "Write every stroke's reading to this JSON file ({\"strokes\": [{\"face\", \"view\", \"mapper\", \"feature\", \"outcome\", "
        "\"across_mm\", \"misread\", ...}]}) and print the strokes read and misread per feature");
    cmd->add_option("-o,--output", c->output, "Folder for colour-coded error renders (blue to red)");
    cmd->add_option("--renders", c->renders, "Test faces to render")->capture_default_str();
    cmd->add_option("--error-scale", c->errorScale, "Error in mm drawn red")->capture_default_str();
    cmd->add_flag("-q,--quiet", c->quiet, "No progress lines");
    cmd->callback([c] { runEvalStrokes(*c); });
}

} // namespace facesketch::app

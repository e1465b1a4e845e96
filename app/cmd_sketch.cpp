// `facesketch sketch`: replays a session file headless (docs/session-format.md): every stroke is
// read (sketch/mapper.h) and applied to the tracking model (sketch/tracking.h); prints per stroke
// the points, candidates, mapped vertices and milliseconds, writes the face and optionally a
// picture of it with the last view's strokes, their interpreted strokes and mapped vertices.

#include "commands.h"
#include "sketch_data.h"

#include "core/error.h"
#include "io/mesh_io.h"
#include "io/png.h"
#include "render/renderer.h"
#include "sketch/feedback.h"
#include "sketch/mapper.h"
#include "sketch/replay.h"
#include "sketch/session.h"
#include "stats/model_file.h"

#include <iomanip>
#include <iostream>
#include <memory>
#include <numeric>
#include <optional>

namespace facesketch::app {

namespace {

struct SketchCommand {
    std::string model, dataset, session, output, render, mapper;
    int similar = 3;
    int refine = -1;                       ///< -1: as each stroke recorded (else the default)
    std::vector<std::string> mapperParams; ///< NAME=VALUE, over what each stroke recorded
};

void runSketch(const SketchCommand& c)
{
    // --mapper-param, checked before anything is loaded.
    std::map<std::string, double> overrides;
    for (const std::string& assignment : c.mapperParams) {
        const auto [name, value] = sketch::parseMapperParam(assignment);
        overrides[name] = value;
    }
    (void)sketch::mapperParamsFrom(overrides); // names, kinds and ranges
    const sketch::Session session = sketch::loadSession(c.session);
    (void)sketch::sessionInputs(session, c.session); // the session's model and dataset must exist
    // -1: each stroke's own mapper (GCC warns about reading an optional here).
    const int override = c.mapper.empty() ? -1 : static_cast<int>(sketch::parseMapper(c.mapper));
    const stats::FaceModel m = stats::loadFaceModel(c.model);
    const SketchData d = loadSketchData(c.dataset, &m);

    gpu::ScopedDevice device;
    // The app replays through the same SessionReplayer (sketch/replay.h): the same face.
    sketch::SessionReplayer replayer(*device, m, d.candidateFaces, d.flags, d.landmarks, c.model);
    if (c.refine >= 0) {
        sketch::RefineOptions refine;
        refine.passes = c.refine;
        replayer.setRefine(refine);
    }
    replayer.setMapperParamOverrides(overrides);
    std::cout << "# " << session.actions.size() << " strokes, " << m.vertexCount() << " vertices, cloud of " << d.candidateFaces.size()
              << " faces\n";
    std::cout << std::fixed << std::setprecision(1);
    struct Drawn {
        sketch::StrokeReading reading;
        OrbitView view;
    };
    std::vector<Drawn> drawn;
    int refused = 0;
    for (size_t i = 0; i < session.actions.size(); ++i) {
        const sketch::StrokeAction& a = session.actions[i];
        std::optional<sketch::MapperKind> kind;
        if (override >= 0)
            kind = static_cast<sketch::MapperKind>(override);
        sketch::ReplayOutcome r = replayer.apply(a, kind);
        if (r.mirrorFound) {
            const sketch::MirrorCheck& k = replayer.mirror()->check();
            std::cout << "# mirror map: plane x = " << k.planeX << " mm, worst pair " << k.maxDistance << " mm (mean edge " << k.meanEdge
                      << " mm), " << k.labelledPairs << " labelled pairs\n";
        }
        std::cout << "stroke " << i << ": " << a.stroke.points.size() << " points, " << sketch::mapperName(r.mapper);
        if (r.kind == sketch::ReplayOutcome::Kind::Refused) {
            // The face and tracking model are as they were; the replay goes on.
            std::cout << ": refused: " << r.error << "\n";
            ++refused;
            continue;
        }
        const int candidates = std::accumulate(r.reading.candidateCounts.begin(), r.reading.candidateCounts.end(), 0);
        std::cout << ", " << r.reading.screenPoints.size() << " densified, " << candidates << " candidates, "
                  << r.reading.observations.size() << " vertices mapped, read " << r.readMs << " ms (candidates " << r.timing.candidatesMs
                  << ", mapping " << r.timing.mappingMs << ")";
        if (r.kind == sketch::ReplayOutcome::Kind::PinsNothing) {
            std::cout << ", pins nothing" << (r.reading.message.empty() ? "" : ": " + r.reading.message) << "\n";
            continue;
        }
        std::cout << ", refined " << r.refinePasses << "x, rebuild " << r.applyMs << " ms, " << replayer.tracking().observedVertices()
                  << " vertices observed\n";
        drawn.push_back({ std::move(r.reading), a.stroke.view });
    }
    const Mesh face = replayer.face();
    writeMesh(c.output, face);
    std::cout << "wrote " << c.output << " (" << replayer.tracking().strokes() << " strokes applied, " << refused << " refused)\n";

    if (c.similar > 0 && !d.trainNames.empty()) {
        const std::vector<Mesh> train(d.candidateFaces.begin(), d.candidateFaces.begin() + static_cast<long>(d.trainNames.size()));
        std::cout << "most similar training faces:";
        for (const auto& [index, mm] : sketch::mostSimilarFaces(face, train, c.similar))
            std::cout << " " << d.trainNames[static_cast<size_t>(index)] << " (" << std::setprecision(2) << mm << " mm)";
        std::cout << "\n";
    }

    if (!c.render.empty()) {
        // The last stroke's view, with every stroke drawn in that view: as drawn (red), as
        // understood (the interpreted stroke, blue) and the mapped vertices (green).
        const OrbitView view = drawn.empty() ? frameMeshView(face, { 0, 0 }, 800, 800) : drawn.back().view;
        const Camera camera = orbitCamera(view);
        Renderer renderer(*device, view.width, view.height, 4);
        renderer.addMesh(face);
        std::vector<glm::vec3> stroke, interpreted, mapped;
        for (const Drawn& s : drawn) {
            if (!sketch::operator==(s.view, view))
                continue;
            // Lines are drawn slightly towards the camera so the surface does not hide them.
            auto lift = [&](const Eigen::Vector3d& x) {
                const glm::dvec3 p(x.x(), x.y(), x.z());
                return glm::vec3(p + 1.0 * camera.toCamera(p));
            };
            for (size_t k = 1; k < s.reading.worldPoints.size(); ++k) {
                stroke.push_back(lift(s.reading.worldPoints[k - 1]));
                stroke.push_back(lift(s.reading.worldPoints[k]));
            }
            const sketch::InterpretedStroke is = sketch::interpretStroke(s.reading, face, camera);
            for (size_t k = 0; k < is.world.size(); ++k) {
                mapped.push_back(lift(is.world[k]));
                if (k > 0) {
                    interpreted.push_back(lift(is.world[k - 1]));
                    interpreted.push_back(lift(is.world[k]));
                }
            }
        }
        renderer.addLines(stroke, std::vector<glm::vec4>(stroke.size(), { 0.85f, 0.1f, 0.1f, 1 }));
        renderer.addLines(interpreted, std::vector<glm::vec4>(interpreted.size(), { 0.1f, 0.2f, 0.9f, 1 }));
        renderer.addPoints(mapped, std::vector<glm::vec4>(mapped.size(), { 0.1f, 0.7f, 0.2f, 1 }), 4.0f);
        writePng(c.render, renderer.render(camera));
        std::cout << "wrote " << c.render << "\n";
    }
}

} // namespace

void addSketchCommand(CLI::App& root)
{
    auto c = std::make_shared<SketchCommand>();
    auto* cmd = root.add_subcommand("sketch", "Replay a session file of strokes headless into a face");
    cmd->footer("Reads every stroke of the session (docs/session-format.md) against the current face, applies it to the\n"
                "tracking model and prints, per stroke: points, densified points, candidates, mapped vertices and\n"
                "milliseconds. A stroke that cannot be read is reported and leaves the face as it was.");
    cmd->add_option("model", c->model, "Model file from `facesketch train`")->required();
    cmd->add_option("dataset", c->dataset, "The dataset it was trained on (its train and contour faces form the candidate cloud)")
        ->required();
    cmd->add_option("--session", c->session, "Session file to replay")->required();
    cmd->add_option("-o,--output", c->output, "The face to write (.ply or .obj)")->required();
    cmd->add_option("--render", c->render, "Also a PNG of the face in the last stroke's view with its strokes");
    cmd->add_option("--mapper", c->mapper, "Read every stroke with this mapper instead of the session's")
        ->check(CLI::IsMember({ "nearest", "heuristic", "hmm", "simple" }));
    cmd->add_option("--refine", c->refine,
           "Refinement passes per stroke: read again against the face its reading rebuilt, with the simple mapper (sketch/refine.h; 0: "
           "the first reading alone). Default: as each stroke recorded, else "
               + std::to_string(sketch::RefineOptions {}.passes))
        ->check(CLI::Range(0, 16));
    cmd->add_option("--mapper-param", c->mapperParams,
        "Read every stroke with this mapper parameter, NAME=VALUE, over what the strokes recorded (repeatable; names as in "
        "sketch/mapper_params.h MapperParams, e.g. sigmaDTau=2; by default each stroke is read with the parameters it recorded, else the "
        "defaults)");
    cmd->add_option("--similar", c->similar, "Print the k most similar training faces")->capture_default_str()->check(CLI::Range(0, 1000));
    cmd->callback([c] { runSketch(*c); });
}

} // namespace facesketch::app

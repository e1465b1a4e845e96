// `facesketch bench sketch`: one stroke of about 60 points from the stroke file to the updated
// face (issue 12), on the synthetic low, high and ultra sets (about 900, 6,000 and 25,000
// vertices): the session file parsed, the stroke read (candidates, mapping) and applied to the
// tracking model (reconstruction), then refined against the rebuilt face (sketch/refine.h: each
// pass a reading and a rebuild more), each part listed, summed over the passes.
#include "bench.h"
#include "sketch_data.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "dataset/synth/synth_dataset.h"
#include "model/head_model.h"
#include "sketch/mapper.h"
#include "sketch/refine.h"
#include "sketch/session.h"
#include "sketch/simulate.h"
#include "sketch/tracking.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace facesketch::app {

namespace {

// The simulated stroke of test face 0 from the front whose point count is nearest 60.
sketch::Stroke benchStroke(const SketchData& d, const Mesh& mean)
{
    sketch::SimulateOptions o;
    o.noisePx = 1.0;
    const sketch::Simulation sim = sketch::simulateStrokes(d.testFaces.front(), mean, d.contours, d.flags, o);
    const sketch::SimulatedStroke* best = nullptr;
    for (const sketch::SimulatedStroke& s : sim.strokes)
        if (!best
            || std::abs(static_cast<long>(s.stroke.points.size()) - 60) < std::abs(static_cast<long>(best->stroke.points.size()) - 60))
            best = &s;
    if (!best)
        fail("bench sketch: no stroke simulated");
    return best->stroke;
}

} // namespace

void benchSketch(const BenchOptions& options, std::ostream& out)
{
    namespace fs = std::filesystem;
    // FACESKETCH_BENCH_RESOLUTIONS=low,high limits the sets (ultra takes the longest to train).
    std::string list = "low,high,ultra";
    if (const char* env = std::getenv("FACESKETCH_BENCH_RESOLUTIONS"))
        list = env;
    const fs::path dir = fs::temp_directory_path() / ("facesketch-bench-sketch-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    gpu::ScopedDevice device;
    std::stringstream names(list);
    for (std::string name; std::getline(names, name, ',');) {
        dataset::SynthOptions s;
        s.resolution = dataset::parseResolution(name);
        const fs::path folder = dir / name;
        dataset::writeSynthDataset(folder, s);
        // A model cheaper to train than the default (fewer candidate component counts and
        // folds): the stroke's cost depends on the topology and the latent sizes, which stay.
        model::HeadModelOptions mo;
        mo.face.components = { 1, 2 };
        mo.face.folds = 3;
        const Stopwatch trainClock;
        const stats::FaceModel model = model::trainHeadModel(dataset::openDataset(folder), mo);
        const SketchData d = loadSketchData(folder.string(), &model);
        const Eigen::Index nv = model.vertexCount();
        out << "# " << name << ": " << nv << " vertices, cloud of " << d.candidateFaces.size() << " faces, model trained in "
            << trainClock.seconds() << " s\n";

        // The stroke goes through a session file, as the app would hand it over.
        sketch::Session session;
        session.model = "bench.model";
        session.dataset = name;
        session.actions.push_back({ benchStroke(d, meanMesh(model)), {} });
        const fs::path file = dir / (name + "-stroke.json");
        sketch::saveSession(file, session);
        out << "# stroke of " << session.actions[0].stroke.points.size() << " points, front view, " << session.actions[0].stroke.view.width
            << " px\n";

        sketch::StrokeReader reader(*device, model, d.candidateFaces, d.flags);
        // The product's reading (the HMM, refined: sketch/refine.h), the same with passes that
        // read all of the face's own lines (not anchored), the HMM's first reading alone, and
        // the nearest mapper's.
        struct Variant {
            sketch::MapperKind kind;
            int passes;
            int anchorRings;
            const char* suffix;
        };
        const sketch::RefineOptions product;
        for (const Variant& variant : { Variant { sketch::MapperKind::Hmm, product.passes, product.anchorRings, "" },
                 Variant { sketch::MapperKind::Hmm, product.passes, -1, "_free" },
                 Variant { sketch::MapperKind::Hmm, 0, product.anchorRings, "_unrefined" },
                 Variant { sketch::MapperKind::Nearest, 0, product.anchorRings, "_nearest" } }) {
            sketch::RefineOptions refine;
            refine.passes = variant.passes;
            refine.anchorRings = variant.anchorRings;
            std::vector<double> total, load, candidates, mapping, rebuild;
            int passes = 0;
            // One untimed run warms the caches and the GPU pipelines.
            for (int r = 0; r <= options.repeat; ++r) {
                sketch::TrackingModel tracking(model);
                Stopwatch clock;
                const sketch::Session loaded = sketch::loadSession(file);
                const double loadMs = clock.milliseconds();
                const sketch::ReadResult done
                    = sketch::readAndApply(reader, tracking, loaded.actions[0].stroke, variant.kind, {}, {}, refine);
                const double all = clock.milliseconds();
                if (r == 0)
                    continue;
                total.push_back(all);
                load.push_back(loadMs);
                candidates.push_back(done.timing.candidatesMs);
                mapping.push_back(done.timing.mappingMs);
                rebuild.push_back(done.applyMs);
                passes = done.passes;
            }
            const std::string suffix = cat(variant.suffix, "_", nv, "v");
            out << "sketch_stroke_ms" << suffix << " " << median(total) << " ms\n";
            out << "sketch_stroke_load_ms" << suffix << " " << median(load) << " ms\n";
            out << "sketch_stroke_candidates_ms" << suffix << " " << median(candidates) << " ms\n";
            out << "sketch_stroke_mapping_ms" << suffix << " " << median(mapping) << " ms\n";
            out << "sketch_stroke_rebuild_ms" << suffix << " " << median(rebuild) << " ms\n";
            if (variant.passes > 0)
                out << "sketch_stroke_refine_passes" << suffix << " " << passes << " passes\n";
        }
        fs::remove_all(folder);
    }
    fs::remove_all(dir);
}

} // namespace facesketch::app

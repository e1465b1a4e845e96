// `facesketch bench train`: the face model trained on the synthetic low, high and ultra sets
// (issue 4). The statistics core alone (`bench stats`) is app/bench_stats.cpp.
#include "bench.h"

#include "core/random.h"
#include "core/stopwatch.h"
#include "dataset/synth/synth_dataset.h"
#include "model/head_assembly.h"
#include "model/head_model.h"
#include "stats/model_file.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <unistd.h>

namespace facesketch::app {

void benchTrain(const BenchOptions& options, std::ostream& out)
{
    namespace fs = std::filesystem;
    // FACESKETCH_BENCH_RESOLUTIONS=low,high limits the sets (ultra takes the longest).
    std::string list = "low,high,ultra";
    if (const char* env = std::getenv("FACESKETCH_BENCH_RESOLUTIONS"))
        list = env;
    const fs::path dir = fs::temp_directory_path() / ("facesketch-bench-train-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    // The thesis' full-covariance model files (Gunnarsson 2010): 338 MB at 863 vertices (its
    // low resolution), 667 MB at 6,174 (high).
    const double thesisMb[3] = { 338.0, 667.0, 667.0 };
    std::stringstream names(list);
    for (std::string name; std::getline(names, name, ',');) {
        const dataset::Resolution res = dataset::parseResolution(name);
        dataset::SynthOptions s;
        s.resolution = res;
        const fs::path folder = dir / name;
        dataset::writeSynthDataset(folder, s);
        const dataset::Dataset ds = dataset::openDataset(folder);
        out << "# " << name << ": " << ds.manifest.vertexCount << " vertices, " << ds.manifest.samplesWithRole(dataset::Role::Train).size()
            << " train faces, default train options\n";

        const Stopwatch clock;
        const stats::FaceModel model = model::trainHeadModel(ds, {});
        out << "train_" << name << "_s " << clock.seconds() << " s\n";
        const fs::path file = dir / (name + ".model");
        stats::saveFaceModel(model, file);
        const double mb = static_cast<double>(fs::file_size(file)) / 1e6;
        out << "model_size_" << name << "_mb " << mb << " MB\n";
        out << "model_size_" << name << "_thesis_ratio " << thesisMb[static_cast<int>(res)] / mb << " x (thesis "
            << thesisMb[static_cast<int>(res)] << " MB" << (res == dataset::Resolution::Ultra ? " at 6,174 vertices)\n" : ")\n");

        // One full reconstruction from 15% of a held-out face's skin vertices: every segment,
        // clean-up and correlation, blended, then the rigid parts placed.
        const Eigen::MatrixXd test = dataset::loadShapes(ds, dataset::Role::Test, "skin");
        Random random(7);
        stats::Observations obs;
        for (Eigen::Index v = 0; v < model.vertexCount(); ++v)
            if (random.uniform() < 0.15)
                obs.addVertex(v, test.row(0).segment<3>(3 * v).transpose());
        std::vector<double> face, head;
        for (int r = 0; r < options.repeat; ++r) {
            Stopwatch t;
            const stats::Reconstruction rec = stats::reconstruct(model, obs);
            face.push_back(t.milliseconds());
            t.restart();
            const Mesh whole = model::assembleHead(model.head, model.meanFace, rec.face);
            head.push_back(t.milliseconds());
        }
        out << "reconstruct_" << name << "_ms " << median(face) << " ms\n";
        out << "reconstruct_head_parts_" << name << "_ms " << median(head) << " ms\n";
        fs::remove_all(folder);
    }
    fs::remove_all(dir);
}

} // namespace facesketch::app

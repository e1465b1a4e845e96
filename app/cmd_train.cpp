// `facesketch train DATASET -o MODEL`: trains the face model of a dataset (issue 4; thesis
// 4.2) and writes it as one model file (stats/model_file.h).
#include "commands.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "model/head_model.h"
#include "stats/model_file.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace facesketch::app {

namespace {

struct TrainCommand {
    std::string dataset;
    std::string output;
    model::HeadModelOptions options;
    bool rigid = false;
    bool quiet = false;
};

// A one-line progress bar redrawn in place on stderr.
stats::TrainProgress progressBar(bool quiet)
{
    if (quiet)
        return {};
    return [](const std::string& what, double fraction) {
        constexpr int width = 30;
        const int filled = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * width + 0.5);
        std::cerr << "\r[" << std::string(static_cast<size_t>(filled), '#') << std::string(static_cast<size_t>(width - filled), ' ') << "] "
                  << std::setw(3) << static_cast<int>(fraction * 100 + 0.5) << "% " << std::left << std::setw(24) << what << std::right
                  << std::flush;
        if (fraction >= 1.0)
            std::cerr << "\n";
    };
}

void runTrain(const TrainCommand& c)
{
    if (c.output.empty())
        fail("train: give the model file to write with -o MODEL");
    model::HeadModelOptions options = c.options;
    options.scale = !c.rigid;
    const dataset::Dataset ds = dataset::openDataset(c.dataset);
    const Stopwatch clock;
    const stats::FaceModel m = model::trainHeadModel(ds, options, progressBar(c.quiet));
    const double seconds = clock.seconds();
    stats::saveFaceModel(m, c.output);

    std::cout << "trained on " << ds.manifest.samplesWithRole(dataset::Role::Train).size() << " faces of " << c.dataset << ": "
              << m.vertexCount() << " skin vertices in " << m.segmentation.size() << " segments (" << std::fixed << std::setprecision(1)
              << seconds << " s)\n"
              << stats::describe(m);
    for (const stats::RigidPart& part : m.head.parts)
        std::cout << "rigid part " << part.name << ": " << part.vertices.size() << " vertices follow " << part.anchors.size()
                  << " skin anchors (" << (part.scale ? "similarity" : "rigid") << ")\n";
    std::cout << "wrote " << c.output << " (" << std::setprecision(2) << static_cast<double>(std::filesystem::file_size(c.output)) / 1e6
              << " MB)\n";
}

} // namespace

void addTrainCommand(CLI::App& root)
{
    auto c = std::make_shared<TrainCommand>();
    stats::FaceModelOptions& f = c->options.face;
    auto* cmd = root.add_subcommand("train", "Train the face model of a dataset (segmented mixtures of PPCA, thesis 4.2)");
    cmd->footer("Trains on the dataset's `train` faces (skin component): segments the mean face (k-means from the\n"
                "nose tip \"prn\", small groups merged, left and right together, blended borders), fits a mixture of\n"
                "PPCA per segment (components chosen by cross-validated likelihood among --components), a clean-up\n"
                "PPCA per segment and a correlation mixture over all segment latents. Every other component (eyes,\n"
                "teeth, tongue) is stored on the mean head and follows its nearest skin vertices. Prints one line\n"
                "per segment: vertices, components, latent dimension, clean-up dimension, log-likelihood per face;\n"
                "then the correlation mixture and the joint whole-face model reconstruction uses (docs/face-model.md).\n"
                "Example: facesketch synth -o faces && facesketch train faces -o faces.model");
    cmd->add_option("dataset", c->dataset, "Dataset folder (facesketch synth or import)")->required();
    cmd->add_option("-o,--output", c->output, "Model file to write (replaced atomically)")->required();
    cmd->add_option("-k,--clusters", f.segmentation.clusters,
           "Segmentation: k-means clusters before merging (thesis: 7 at low, 41 at high resolution)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    cmd->add_option(
           "--max-segment-vertices", f.segmentation.maxVertices, "Segmentation: merges never make a segment larger (size threshold)")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000000));
    cmd->add_option("--min-segment-vertices", f.segmentation.minVertices, "Segmentation: smaller groups are merged into a neighbour")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000000));
    cmd->add_option("--overlap", f.segmentation.overlapRings,
           "Segmentation: rings of neighbours shared across a border and blended (0: hard borders)")
        ->capture_default_str()
        ->check(CLI::Range(0, 100));
    cmd->add_option("--latent-dim", f.latentDim, "Latent dimension of each segment mixture component")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000));
    cmd->add_option(
           "--components", f.components, "Candidate numbers of mixture components per segment; the best by held-out likelihood wins")
        ->capture_default_str()
        ->check(CLI::Range(1, 100))
        ->delimiter(',');
    cmd->add_option("--folds", f.folds, "Cross-validation folds for choosing the number of components")
        ->capture_default_str()
        ->check(CLI::Range(2, 100));
    cmd->add_option("--cleanup-dim", f.cleanUpDim, "Latent dimension of each segment's clean-up PPCA, at most")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000));
    cmd->add_option("--cleanup-variance", f.cleanUpVariance,
           "Each segment's clean-up keeps the fewest latent dimensions holding this fraction of its variance (1: --cleanup-dim everywhere)")
        ->capture_default_str()
        ->check(CLI::Range(1e-6, 1.0));
    cmd->add_option("--correlation-components", f.correlationComponents, "Components of the correlation mixture")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    cmd->add_option("--correlation-dim", f.correlationLatentDim, "Latent dimension of the correlation mixture")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000));
    cmd->add_option("--restarts", f.mppca.restarts, "EM runs from different starts per mixture (best kept)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    cmd->add_option("--threads", f.threads, "Threads fitting the segments (0: all hardware threads; the model is the same for any number)")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    cmd->add_option("--anchors", c->options.anchors, "Skin vertices each rigid part (eyeball, teeth, tongue) follows")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000));
    cmd->add_flag("--rigid", c->rigid, "Rigid parts follow the skin by rotation and translation only (default: also scale)");
    cmd->add_flag("-q,--quiet", c->quiet, "No progress bar");
    cmd->callback([c] { runTrain(*c); });
}

} // namespace facesketch::app

// `facesketch eval`: measurements of a trained face model on a dataset's held-out faces.
//   eval observe   reconstruct each `test` face from a random fraction, or one feature region,
//                  of its own skin vertices (issue 4); errors in mm beside the mean face's.
// Further measurements are sub-subcommands of `eval`, each added by its own function below.
#include "commands.h"

#include "core/error.h"
#include "evaluation/evaluate.h"
#include "model/head_model.h"
#include "model/regions.h"
#include "stats/model_file.h"

#include <iomanip>
#include <iostream>

namespace facesketch::app {

namespace {

struct ObserveCommand {
    std::string model;
    std::string dataset;
    double fraction = 0.15;
    std::string region;
    double radius = 10.0;
    bool noCorrelation = false;
    std::string correlation = "joint";
    bool noCleanUp = false;
    std::uint64_t seed = 1;
};

void runObserve(const ObserveCommand& c)
{
    const stats::FaceModel m = stats::loadFaceModel(c.model);
    const dataset::Dataset ds = dataset::openDataset(c.dataset);
    model::requireModelFits(m, ds.manifest, c.dataset);
    const Eigen::MatrixXd test = dataset::loadShapes(ds, dataset::Role::Test, "skin");
    if (test.rows() == 0)
        fail(c.dataset, ": no `test` samples to evaluate on");

    evaluation::ObserveOptions o;
    o.fraction = c.fraction;
    o.seed = c.seed;
    o.reconstruct.correlation = c.noCorrelation ? stats::Correlation::Off : stats::parseCorrelation(c.correlation);
    o.reconstruct.cleanUp = !c.noCleanUp;
    if (!c.region.empty()) {
        o.region = model::featureRegion(ds.manifest, m, c.region, c.radius);
        if (o.region.empty())
            fail("region ", c.region, " holds no vertex within ", c.radius, " mm of its landmarks");
    }
    const evaluation::ObserveScore s = evaluation::evaluateObserve(m, test, o);

    std::cout << std::fixed << std::setprecision(2);
    std::cout << "# " << s.faces << " test faces of " << c.dataset << ", " << m.vertexCount() << " skin vertices, measured "
              << (c.region.empty() ? "at random" : "region " + c.region) << ": " << 100.0 * s.measuredFraction
              << "% of the vertices; clean-up " << (o.reconstruct.cleanUp ? "on" : "off") << ", correlation "
              << stats::correlationName(o.reconstruct.correlation) << "\n";
    std::cout << std::setw(14) << "" << std::setw(12) << "mean mm" << std::setw(12) << "max mm"
              << "\n"
              << std::setw(14) << "reconstruction" << std::setw(12) << s.meanError << std::setw(12) << s.maxError << "\n"
              << std::setw(14) << "mean face" << std::setw(12) << s.meanFaceMeanError << std::setw(12) << s.meanFaceMaxError << "\n";
    std::cout << "ratio " << std::setprecision(3) << s.meanError / s.meanFaceMeanError << " of the mean face's error (95% interval "
              << s.ratioInterval.low << "-" << s.ratioInterval.high << " over the draw of the faces), " << s.millisecondsPerFace
              << " ms per face\n";
}

void addObserveCommand(CLI::App& eval)
{
    auto c = std::make_shared<ObserveCommand>();
    auto* cmd = eval.add_subcommand("observe", "Reconstruct held-out faces from some of their own vertices; errors in mm");
    cmd->footer("For every `test` face of DATASET, measures a random fraction of its skin vertices (or all those of one\n"
                "region) in 3D, reconstructs the face with MODEL and prints the mean and max per-vertex error in mm,\n"
                "beside the error of the model's mean face, and their ratio with its 95% interval over the draw of the faces\n"
                "(a bootstrap: with 20 test faces a ratio moves by several hundredths with the faces alone).\n"
                "Regions: nose, mouth, chin, eyes, brows, mouth_chin, eyes_brows (skin vertices within --radius mm of\n"
                "the region's landmarks and contours in the manifest, on the mean face), or segment:N (the core of\n"
                "segment N as `facesketch train` lists them).");
    cmd->add_option("model", c->model, "Model file (facesketch train)")->required();
    cmd->add_option("dataset", c->dataset, "Dataset folder the model was trained on")->required();
    cmd->add_option("--fraction", c->fraction, "Fraction of the vertices measured, drawn per face")
        ->capture_default_str()
        ->check(CLI::Range(1e-9, 1.0));
    cmd->add_option("--region", c->region, "Measure exactly one region's vertices instead (see below)");
    cmd->add_option("--radius", c->radius, "Region radius around its landmarks, mm")->capture_default_str()->check(CLI::Range(0.0, 1000.0));
    cmd->add_option("--correlation", c->correlation,
           "How measured segments inform the others: joint (all measurements condition one whole-face "
           "model), thesis (4.2.5: segment latents completed by the correlation mixture) or off")
        ->check(CLI::IsMember({ "joint", "thesis", "off" }))
        ->capture_default_str();
    cmd->add_flag("--no-correlation", c->noCorrelation, "Same as --correlation off: unmeasured segments keep the mean face");
    cmd->add_flag("--no-cleanup", c->noCleanUp, "Skip the clean-up projection of each segment (thesis 4.2.4)");
    cmd->add_option("--seed", c->seed, "Seed of the random choice of measured vertices")->capture_default_str();
    cmd->callback([c] { runObserve(*c); });
}

} // namespace

void addEvalCommand(CLI::App& root)
{
    auto* eval = root.add_subcommand("eval", "Measure a trained face model on a dataset's held-out faces");
    eval->require_subcommand(1);
    addObserveCommand(*eval);
    addEvalContoursCommand(*eval);
    addEvalStrokesCommand(*eval);
    addEvalPosesCommand(*eval);
    addEvalRealismCommand(*eval);
}

} // namespace facesketch::app

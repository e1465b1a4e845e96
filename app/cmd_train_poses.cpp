// `facesketch train-poses DATASET -o POSES.model`: trains the pose model of a posed dataset
// (issue 13; thesis Ch. 5) and writes it as one file (pose/pose_file.h).
#include "commands.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "pose/minimal_poses.h"
#include "pose/pose_file.h"
#include "pose/pose_model.h"

#include <filesystem>
#include <iomanip>
#include <iostream>

namespace facesketch::app {

namespace {

struct TrainPosesCommand {
    std::string dataset;
    std::string output;
    std::string minimal;
    pose::PoseModelOptions options;
};

void runTrainPoses(const TrainPosesCommand& c)
{
    const dataset::Dataset ds = dataset::openDataset(c.dataset);
    const std::vector<pose::MinimalPose> minimal = c.minimal.empty() ? pose::loadMinimalPoses() : pose::readMinimalPoses(c.minimal);
    const Stopwatch clock;
    const pose::PoseSet all = pose::loadPoseSet(ds, { dataset::Role::Train, dataset::Role::Contour });
    const pose::PoseSet train = pose::selectRole(all, dataset::Role::Train);
    const pose::PoseSet contour = pose::selectRole(all, dataset::Role::Contour);
    if (train.identityCount() == 0)
        fail(c.dataset, ": no `train` identity has poses");
    // The `contour` identities choose the number of completion components when they have poses;
    // otherwise the training identities do.
    const pose::PoseSet& validation = contour.identityCount() > 0 ? contour : train;
    const double loadSeconds = clock.seconds();
    const pose::PoseModel m = pose::trainPoseModel(train, validation, minimal, c.options);
    const double seconds = clock.seconds() - loadSeconds;
    pose::savePoseModel(m, c.output);

    std::cout << std::fixed << std::setprecision(2);
    std::cout << "trained on " << train.identityCount() << " identities x " << train.poseCount() << " poses of " << c.dataset << " ("
              << m.vertexCount << " vertices, " << m.fpCount() << " MPEG-4 feature points; loaded in " << loadSeconds << " s, trained in "
              << seconds << " s)\n";
    std::cout << "completion (thesis 5.4): K chosen on " << validation.identityCount() << " "
              << (&validation == &contour ? "contour" : "train") << " identities by the minimal-pose error\n";
    std::cout << std::setw(6) << "K" << std::setw(8) << "fitted" << std::setw(4) << "q" << std::setw(16) << "minimal mm/FP" << std::setw(20)
              << "log-lik per pose\n";
    for (const pose::CompletionScore& s : m.completion.scores)
        std::cout << std::setw(6) << s.components << std::setw(8) << s.fitted << std::setw(4) << s.latentDim << std::setw(16)
                  << s.minimalError << std::setw(19) << s.logLikelihood << "\n";
    std::cout << "primary " << m.completion.primary.size() << " components of q = " << m.completion.primary.components.front().latentDim()
              << ", alternative " << m.completion.alternative.size()
              << " components of q = " << m.completion.alternative.components.front().latentDim() << "\n";
    std::cout << "mapping (thesis 5.4.1): FP PPCA q = " << m.mapping.fp.latentDim() << ", mesh PPCA q = " << m.mapping.mesh.latentDim()
              << ", joint mixture " << m.mapping.joint.size()
              << " components of q = " << (m.mapping.joint.size() ? m.mapping.joint.components.front().latentDim() : 0) << "\n";
    std::cout << "wrote " << c.output << " (" << static_cast<double>(std::filesystem::file_size(c.output)) / 1e6 << " MB)\n";
}

} // namespace

void addTrainPosesCommand(CLI::App& root)
{
    auto c = std::make_shared<TrainPosesCommand>();
    auto* cmd
        = root.add_subcommand("train-poses", "Train the pose model of a posed dataset (completion and FP-to-mesh mapping, thesis Ch. 5)");
    cmd->footer("Learns poses as displacements from each identity's neutral, so the model poses any face of the topology:\n"
                "a mixture of PPCA over whole MPEG-4 feature-point poses completes the points a user did not draw, its\n"
                "number of components chosen by how well it rebuilds poses from the minimal-pose table (the `contour`\n"
                "identities' poses if they have any, else the training ones), with the runner-up kept as the alternative\n"
                "interpretation; dual PPCA on the FP poses and the mesh poses and a mixture on their joined latents map\n"
                "an FP pose to the mesh (docs/posing.md).\n"
                "Example: facesketch synth -o posed --identities 40 --poses && facesketch train-poses posed -o posed.poses");
    cmd->add_option("dataset", c->dataset, "Posed dataset folder (facesketch synth --poses, import ict-facekit --poses)")->required();
    cmd->add_option("-o,--output", c->output, "Pose model file to write (replaced atomically)")->required();
    cmd->add_option("--minimal", c->minimal, "Minimal-pose table (default: the installed minimal-poses.json asset)");
    cmd->add_option("--components", c->options.completion.candidates, "Candidate numbers of completion components")
        ->capture_default_str()
        ->check(CLI::Range(1, 100))
        ->delimiter(',');
    cmd->add_option("--latent-dims", c->options.completion.latentDims, "Candidate latent dimensions of the completion components")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000))
        ->delimiter(',');
    cmd->add_option("--fp-dim", c->options.mapping.fpLatentDim, "Mapping: latent dimension of the FP PPCA")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--mesh-dim", c->options.mapping.meshLatentDim, "Mapping: latent dimension of the mesh PPCA")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--joint-components", c->options.mapping.components, "Mapping: components of the mixture on the joined latents")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    cmd->add_option("--joint-dim", c->options.mapping.jointLatentDim, "Mapping: latent dimension of the joint mixture")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--threads", c->options.completion.threads,
           "Threads fitting the completion candidates (0: all hardware threads; the model is the same for any number)")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    cmd->callback([c] { runTrainPoses(*c); });
}

} // namespace facesketch::app

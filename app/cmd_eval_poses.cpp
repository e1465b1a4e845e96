// `facesketch eval poses POSES.model DATASET --json OUT`: completion from minimal feature points
// and FP-to-mesh mapping (statistical vs RBF) on the `test` identities (evaluation/pose_eval.h).
#include "commands.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "evaluation/pose_eval.h"
#include "pose/minimal_poses.h"
#include "pose/pose_file.h"
#include "pose/stroke_eval.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

namespace facesketch::app {

namespace {

struct EvalPosesCommand {
    std::string model, dataset, json, minimal;
    std::string identities = "test";
    pose::PoseStrokeOptions strokes;
};

void runEvalPoses(const EvalPosesCommand& c)
{
    if (c.identities != "test" && c.identities != "contour")
        fail("eval poses: --identities ", c.identities, ": expected test or contour");
    if (!(c.strokes.reading.endpointWeight >= 1) || !std::isfinite(c.strokes.reading.endpointWeight))
        fail("eval poses: --endpoint-weight ", c.strokes.reading.endpointWeight, " is not a finite value >= 1");
    const pose::PoseModel m = pose::loadPoseModel(c.model);
    const dataset::Dataset ds = dataset::openDataset(c.dataset);
    const std::vector<pose::MinimalPose> minimal = c.minimal.empty() ? pose::loadMinimalPoses() : pose::readMinimalPoses(c.minimal);
    // `contour` identities (which train-poses used only to choose the mixture) are where reading
    // parameters are fitted; `test` identities are where they are reported.
    const pose::PoseSet test = pose::loadPoseSet(ds, { c.identities == "contour" ? dataset::Role::Contour : dataset::Role::Test });
    evaluation::PoseEvaluation e = evaluation::evaluatePoses(m, test, minimal);
    // (c) from simulated pose strokes (front view, lip and brow contours): the whole chain a
    // user drives, strokes -> FPs (5.3) -> completion (5.4) -> mapping (5.4.1).
    const pose::StrokePoseEvaluation strokes = pose::evaluateStrokePoses(m, test, ds.manifest.contours, {}, c.strokes);
    e.results.push_back(strokes.record);
    e.perPose.insert(e.perPose.end(), strokes.perPose.begin(), strokes.perPose.end());

    std::cout << "# " << e.identities << " " << c.identities << " identities of " << c.dataset << ", " << m.vertexCount
              << " vertices; mean per-vertex error\n";
    std::cout << "# strokes: " << strokes.strokes << " simulated, " << strokes.refused << " refused by the reader\n";
    std::cout << std::fixed << std::setprecision(3) << std::left << std::setw(12) << "task" << std::setw(13) << "method" << std::right
              << std::setw(7) << "poses" << std::setw(10) << "mean mm" << std::setw(9) << "ratio\n";
    for (const evaluation::PoseEvalRecord& r : e.results)
        std::cout << std::left << std::setw(12) << r.task << std::setw(13) << r.method << std::right << std::setw(7) << r.poses
                  << std::setw(10) << r.meanMm << std::setw(8) << r.ratio << "\n";
    if (!c.json.empty()) {
        nlohmann::json results = nlohmann::json::array();
        for (const evaluation::PoseEvalRecord& r : e.results)
            results.push_back(
                { { "task", r.task }, { "method", r.method }, { "poses", r.poses }, { "mean_mm", r.meanMm }, { "ratio", r.ratio } });
        nlohmann::json perPose = nlohmann::json::array();
        for (const evaluation::PosePoseError& p : e.perPose)
            perPose.push_back(
                { { "pose", p.pose }, { "task", p.task }, { "method", p.method }, { "mean_mm", p.meanMm }, { "neutral_mm", p.neutralMm } });
        const nlohmann::json doc { { "model", c.model }, { "dataset", c.dataset }, { "vertices", m.vertexCount },
            { "identities", e.identities }, { "role", c.identities }, { "endpoint_weight", c.strokes.reading.endpointWeight },
            { "results", results }, { "per_pose", perPose } };
        writeFileAtomically(c.json, [&](std::ostream& out) { out << doc.dump(1) << "\n"; });
        std::cout << "wrote " << c.json << "\n";
    }
}

} // namespace

void addEvalPosesCommand(CLI::App& eval)
{
    auto c = std::make_shared<EvalPosesCommand>();
    auto* cmd = eval.add_subcommand("poses", "Pose held-out identities: completion from minimal FPs, FP-to-mesh mapping vs RBF");
    cmd->footer("For every `test` identity of DATASET and every pose but neutral: (a) completes the pose from the FPs of\n"
                "the minimal-pose table and rebuilds the mesh by the statistical mapping (primary and alternative mixture);\n"
                "(b) maps the true FPs to the mesh by the statistical mapping and by the RBF deformation of the identity's\n"
                "neutral. Prints the mean per-vertex error in mm and its ratio to leaving the face neutral; --json writes\n"
                "{\"results\": [{\"task\", \"method\", \"poses\", \"mean_mm\", \"ratio\"}], \"per_pose\": [...]} (docs/posing.md).");
    cmd->add_option("model", c->model, "Pose model file (facesketch train-poses)")->required();
    cmd->add_option("dataset", c->dataset, "Posed dataset with `test` identities (same topology)")->required();
    cmd->add_option("--json", c->json, "Write the records to this JSON file");
    cmd->add_option("--minimal", c->minimal, "Minimal-pose table (default: the installed minimal-poses.json asset)");
    cmd->add_option("--identities", c->identities, "Which identities are posed: test, or contour (to fit reading parameters on)")
        ->capture_default_str();
    cmd->add_option("--endpoint-weight", c->strokes.reading.endpointWeight,
           "Pose strokes: how much a stroke's ends count towards its group and its FPs, >= 1 (pose/stroke_fps.h)")
        ->capture_default_str();
    cmd->callback([c] { runEvalPoses(*c); });
}

} // namespace facesketch::app

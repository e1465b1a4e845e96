#include "evaluation/pose_eval.h"

#include "core/error.h"
#include "pose/completion.h"
#include "pose/mapping.h"

#include <map>

namespace facesketch::evaluation {

namespace {

// Mean over vertices of the distance between two 3#V vectors.
double meanVertexError(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b)
{
    const Eigen::Index n = a.size() / 3;
    double total = 0.0;
    for (Eigen::Index v = 0; v < n; ++v)
        total += (a.segment<3>(3 * v) - b.segment<3>(3 * v)).norm();
    return total / static_cast<double>(n);
}

// Sums of one method's errors and of the neutral baseline's over the pairs it was measured on.
struct Tally {
    double sum = 0.0, neutral = 0.0;
    int pairs = 0;
    std::map<std::string, std::pair<double, double>> byPose; // pose -> (sum, neutral sum)
    void add(const std::string& pose, double error, double neutralError)
    {
        sum += error;
        neutral += neutralError;
        ++pairs;
        auto& p = byPose[pose];
        p.first += error;
        p.second += neutralError;
    }
};

} // namespace

PoseEvaluation evaluatePoses(const pose::PoseModel& model, const pose::PoseSet& test, const std::vector<pose::MinimalPose>& minimal)
{
    if (test.identityCount() == 0)
        fail("eval poses: the dataset has no `test` identity with poses");
    if (test.vertexCount != model.vertexCount || test.topology != model.topology)
        fail("eval poses: the dataset's topology (", test.vertexCount, " vertices) is not the one the pose model was trained on (",
            model.vertexCount, " vertices)");
    if (test.fps.names != model.fps.names || test.fps.vertices != model.fps.vertices)
        fail("eval poses: the dataset's MPEG-4 feature points differ from the pose model's");

    const Eigen::Index I = test.identityCount();
    std::map<std::string, const pose::MinimalPose*> table;
    for (const pose::MinimalPose& entry : minimal)
        table[entry.pose] = &entry;

    Tally mixture, alternative, statistical, rbf, neutralAll;
    Eigen::VectorXd mapped;
    for (Eigen::Index p = 0; p < test.poseCount(); ++p) {
        const std::string& name = test.poseNames[static_cast<size_t>(p)];
        if (name == "neutral")
            continue;
        std::vector<std::string> observed;
        if (const auto it = table.find(name); it != table.end())
            for (const std::string& fp : it->second->fps)
                if (test.fps.index(fp) >= 0)
                    observed.push_back(fp);
        for (Eigen::Index i = 0; i < I; ++i) {
            const Eigen::Index row = test.row(i, p);
            const Eigen::VectorXd truth = test.meshDisplacements.row(row).transpose();
            const Eigen::VectorXd fp = test.fpDisplacements.row(row).transpose();
            const Eigen::VectorXd zero = Eigen::VectorXd::Zero(truth.size());
            const double neutral = meanVertexError(zero, truth);
            neutralAll.add(name, neutral, neutral);

            pose::mapToMesh(model.mapping, fp, mapped);
            statistical.add(name, meanVertexError(mapped, truth), neutral);
            const Eigen::VectorXd face = test.neutrals.row(i).transpose();
            const Vertices neutralFace = asVertices(face);
            const Vertices warped = pose::rbfPose(neutralFace, test.fps, fp);
            const Eigen::VectorXd rbfDisplacement = asVector(warped) - face;
            rbf.add(name, meanVertexError(rbfDisplacement, truth), neutral);

            if (observed.empty())
                continue;
            const stats::Observations obs = pose::observeFps(test.fps, fp, observed);
            for (auto [which, tally] :
                { std::pair { pose::Interpretation::Primary, &mixture }, std::pair { pose::Interpretation::Alternative, &alternative } }) {
                const pose::Completion c = pose::completePose(model, obs, which);
                pose::mapToMesh(model.mapping, c.fp, mapped);
                tally->add(name, meanVertexError(mapped, truth), neutral);
            }
        }
    }
    if (mixture.pairs == 0)
        fail("eval poses: no pose of the minimal-pose table is in the dataset");

    PoseEvaluation out;
    out.identities = static_cast<int>(I);
    auto record = [&](const char* task, const char* method, const Tally& t) {
        const int poses = static_cast<int>(t.byPose.size());
        const double mean = t.sum / t.pairs;
        out.results.push_back({ task, method, poses, mean, t.sum / t.neutral });
        for (const auto& [pose, sums] : t.byPose)
            out.perPose.push_back({ pose, task, method, sums.first / static_cast<double>(I), sums.second / static_cast<double>(I) });
    };
    record("neutral", "neutral", neutralAll);
    record("completion", "mixture", mixture);
    record("completion", "alternative", alternative);
    record("mapping", "statistical", statistical);
    record("mapping", "rbf", rbf);
    return out;
}

} // namespace facesketch::evaluation

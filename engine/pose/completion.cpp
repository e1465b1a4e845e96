#include "pose/completion.h"

#include "core/error.h"
#include "core/parallel.h"
#include "stats/check.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace facesketch::pose {

namespace {

Completion fromInference(const stats::Inference& inference)
{
    return { inference.reconstruction, inference.winner, inference.posterior };
}

} // namespace

Completion complete(const stats::Mppca& mixture, const stats::Observations& observed, double noiseMm)
{
    if (mixture.size() == 0)
        fail("complete: the completion mixture has no components");
    // isfinite first: an ordered comparison with NaN raises the invalid flag (trapped in tests).
    if (!std::isfinite(noiseMm) || noiseMm < 0)
        fail("complete: observation noise ", noiseMm, " mm is not a finite value >= 0");
    observed.validate(mixture.dim());
    if (noiseMm == 0)
        return fromInference(stats::infer(mixture, observed));
    // Independent observation noise adds to the isotropic noise of every component: the same
    // mixture with sigma_k^2 + noise^2 (a copy: 3F by q per component, small).
    stats::Mppca noisy = mixture;
    for (stats::Ppca& c : noisy.components)
        c.sigma2 += noiseMm * noiseMm;
    return fromInference(stats::infer(noisy, observed));
}

stats::Observations observeFps(const FeaturePoints& fps, const Eigen::Ref<const Eigen::VectorXd>& fp, const std::vector<std::string>& names)
{
    if (fp.size() != 3 * fps.size())
        fail("observeFps: an FP pose of ", fp.size(), " values, expected 3 x ", fps.size(), " feature points");
    stats::Observations observed;
    for (const std::string& name : names) {
        const int i = fps.index(name);
        if (i < 0)
            fail("observeFps: no feature point '", name, "' in this topology");
        observed.addVertex(i, fp.segment<3>(3 * i));
    }
    return observed;
}

namespace {

// The entries of the table usable on `set`: pose present, FPs restricted to the ones labelled.
std::vector<std::pair<int, std::vector<std::string>>> usableEntries(const PoseSet& set, const std::vector<MinimalPose>& minimal)
{
    std::vector<std::pair<int, std::vector<std::string>>> out;
    for (const MinimalPose& entry : minimal) {
        const int pose = set.poseIndex(entry.pose);
        if (pose < 0)
            continue;
        std::vector<std::string> names;
        for (const std::string& fp : entry.fps)
            if (set.fps.index(fp) >= 0)
                names.push_back(fp);
        if (!names.empty())
            out.emplace_back(pose, std::move(names));
    }
    return out;
}

} // namespace

double minimalPoseError(const stats::Mppca& mixture, const PoseSet& set, const std::vector<MinimalPose>& minimal)
{
    const auto entries = usableEntries(set, minimal);
    if (entries.empty() || set.identityCount() == 0)
        fail("minimalPoseError: no entry of the minimal-pose table names a pose and a feature point of this set");
    double total = 0.0;
    long count = 0;
    for (const auto& [pose, names] : entries)
        for (Eigen::Index i = 0; i < set.identityCount(); ++i) {
            const Eigen::VectorXd target = set.fpDisplacements.row(set.row(i, pose)).transpose();
            const Completion c = complete(mixture, observeFps(set.fps, target, names));
            const Eigen::VectorXd diff = c.fp - target;
            for (Eigen::Index f = 0; f < set.fps.size(); ++f)
                total += diff.segment<3>(3 * f).norm();
            count += set.fps.size();
        }
    return total / static_cast<double>(count);
}

CompletionModel fitCompletion(
    const Eigen::MatrixXd& train, const PoseSet& validation, const std::vector<MinimalPose>& minimal, const CompletionOptions& options)
{
    const Eigen::Index d = 3 * validation.fps.size();
    if (train.cols() != d)
        fail("fitCompletion: training FP poses have ", train.cols(), " values, expected 3 x ", validation.fps.size(), " feature points");
    stats::requireFinite(train, "fitCompletion: train");
    if (usableEntries(validation, minimal).empty())
        fail("fitCompletion: no entry of the minimal-pose table names a pose and a feature point of the validation set");
    if (options.candidates.empty())
        fail("fitCompletion: no candidate numbers of components");

    // The candidates (K, q) in the order they are scored; bad values fail here, before any fit.
    if (options.latentDims.empty())
        fail("fitCompletion: no candidate latent dimensions");
    std::vector<std::pair<int, int>> grid;
    for (int K : options.candidates) {
        if (K < 1)
            fail("fitCompletion: candidate ", K, " components (must be >= 1)");
        if (K > train.rows())
            continue;
        for (int q : options.latentDims) {
            if (q < 1)
                fail("fitCompletion: candidate latent dimension ", q, " (must be >= 1)");
            grid.emplace_back(K, static_cast<int>(std::min<Eigen::Index>(q, d - 1)));
        }
    }

    // Every candidate is fitted and scored on its own, so they run on all threads, each into its
    // own slot; the choice below reads the slots in grid order, as one thread would.
    struct Fitted {
        CompletionScore score;
        stats::Mppca model;
    };
    std::vector<std::optional<Fitted>> slots(grid.size());
    parallelFor(static_cast<int>(grid.size()), options.threads, [&](int i) {
        const auto [K, q] = grid[static_cast<size_t>(i)];
        stats::MppcaOptions o;
        o.components = K;
        o.latentDim = q;
        o.restarts = options.restarts;
        stats::MppcaFit fit;
        try {
            fit = stats::fitMppca(train, o);
        } catch (const stats::DegenerateFit&) {
            return;
        }
        Fitted f;
        f.model = std::move(fit.model);
        f.score.components = K;
        f.score.fitted = static_cast<int>(f.model.size());
        f.score.latentDim = q;
        f.score.minimalError = minimalPoseError(f.model, validation, minimal);
        f.score.logLikelihood = stats::logLikelihood(f.model, train).mean();
        slots[static_cast<size_t>(i)] = std::move(f);
    });
    std::vector<Fitted> fitted;
    for (std::optional<Fitted>& f : slots)
        if (f)
            fitted.push_back(std::move(*f));
    if (fitted.empty())
        fail("fitCompletion: no candidate (components, latent dimension) could be fit on ", train.rows(), " poses");

    CompletionModel out;
    for (const Fitted& f : fitted)
        out.scores.push_back(f.score);
    std::vector<size_t> order(fitted.size());
    for (size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    // Stable: on equal errors the earlier (smaller) candidate wins.
    std::stable_sort(
        order.begin(), order.end(), [&](size_t a, size_t b) { return fitted[a].score.minimalError < fitted[b].score.minimalError; });
    out.primary = fitted[order[0]].model;
    out.alternative = out.primary;
    for (size_t i = 1; i < order.size(); ++i)
        if (fitted[order[i]].score.fitted != fitted[order[0]].score.fitted) {
            out.alternative = fitted[order[i]].model;
            break;
        }
    return out;
}

} // namespace facesketch::pose

#pragma once
// Pose completion (thesis 5.4): a mixture of PPCA over whole FP poses (3F-vectors of FP
// displacements, pose_data.h) fills in the feature points a user did not draw, by the
// conditional mean under the most probable component (stats/conditional.h, thesis 4.2.1.6).
//
// Choosing the number of components (thesis 5.4): fit mixtures of K = 1..m components (each
// with a few latent dimensions q, see CompletionOptions) and keep the one that best rebuilds
// whole poses from a table of minimal incomplete poses (minimal_poses.h), i.e. the smallest total
// error xi_K = sum_i |r_i - p_i| over the table's entries, here on every validation identity;
// the training log-likelihood is recorded beside it. Two mixtures with close errors may read an
// ambiguous input differently (a wide upper lip: open or closed smile, figs. 5.10 and 5.11); the
// best fit with another number of components is kept as the alternative interpretation the user
// may switch to.
//
// Everything is in double precision; no 3F by 3F covariance is formed (stats/mppca.h).

#include "pose/minimal_poses.h"
#include "pose/pose_data.h"
#include "stats/conditional.h"
#include "stats/mppca.h"

#include <Eigen/Core>
#include <vector>

namespace facesketch::pose {

/// The completion of one incomplete FP pose.
struct Completion {
    /// 3F FP displacements (mm): the observed coordinates as given, the rest their conditional
    /// mean under the winning component.
    Eigen::VectorXd fp;
    /// Component with the highest posterior, and every component's p(k | observed).
    int winner = 0;
    Eigen::VectorXd posterior;
};

/// Completes an FP pose from observations of some FPs. `observed` measures the 3F-vector of FP
/// displacements with FP i as "vertex" i (stats::Observations::addVertex(i, displacement), or
/// addProjectedVertex(i, P, P * displacement) for a stroke seen in a view, whose depth then
/// comes from the model, thesis 5.3 and eq. 4.21). With no observations the result is the mean
/// of the component of highest prior.
///
/// `noiseMm` (>= 0) is the standard deviation of each observed coordinate's own error, in mm:
/// 0 for exact FPs (the minimal table), the reading's error for FPs read from strokes
/// (PoseStrokeOptions::readingNoiseMm). It is added to every component's sigma^2 where the
/// component is chosen and its latents inferred: y = P t + e with e ~ N(0, noiseMm^2 I). A
/// component fitted on a few distinct poses has a tiny sigma^2 (0.02 mm^2 for the open-mouth
/// poses of the tests' posing world), so without it a drawn FP 2 mm off its pose ruled that
/// component out and a closed-mouth one completed an open jaw (docs/posing.md). The observed
/// coordinates are still returned as given. Throws Error if an observation lies outside the 3F
/// vector, a coordinate is measured twice, the mixture is empty or noiseMm is negative or not
/// finite.
Completion complete(const stats::Mppca& mixture, const stats::Observations& observed, double noiseMm = 0.0);

/// Observations of the FPs `names` of the full FP pose `fp` (3F): each FP named is observed in
/// full. Throws Error naming an FP that `fps` lacks.
stats::Observations observeFps(
    const FeaturePoints& fps, const Eigen::Ref<const Eigen::VectorXd>& fp, const std::vector<std::string>& names);

struct CompletionOptions {
    /// Numbers of components to try (thesis: 1..m), each >= 1.
    std::vector<int> candidates { 1, 2, 3, 4, 5, 6, 8, 10 };
    /// Latent dimensions to try with every K (each clamped below the FP dimension 3F). A
    /// component needs more distinct poses than its latent dimension, or its noise variance
    /// collapses and EM drops it (stats/mppca.h): when identities share their expressions (the
    /// ICT blendshapes are the same deltas on every identity) there are only 36 distinct FP
    /// poses, and a large K needs a small q. So (K, q) is chosen together.
    std::vector<int> latentDims { 2, 4, 8 };
    /// EM restarts per fit (stats/mppca.h MppcaOptions::restarts).
    int restarts = 2;
    /// Threads fitting the candidates (0: one per hardware thread); the model and the scores
    /// are the same for any number.
    int threads = 0;
};

/// How one candidate (K, q) did.
struct CompletionScore {
    /// K asked for, and the components left after EM dropped collapsed ones.
    int components = 0;
    int fitted = 0;
    /// Latent dimension q of every component.
    int latentDim = 0;
    /// Mean per-FP error (mm) of the poses rebuilt from the minimal table, over every entry and
    /// every validation identity: xi_K divided by the count of FPs rebuilt.
    double minimalError = 0.0;
    /// Mean training log-likelihood per pose (nats).
    double logLikelihood = 0.0;
};

struct CompletionModel {
    /// The mixture of the lowest minimalError (the one completion uses by default).
    stats::Mppca primary;
    /// The mixture of the lowest minimalError among those with another number of fitted
    /// components (figs. 5.10, 5.11); equal to primary if every fit has the same number.
    stats::Mppca alternative;
    /// One score per candidate (K, q) that could be fit, K-major in the order of the options.
    std::vector<CompletionScore> scores;
};

/// Fits the completion mixtures and chooses K (thesis 5.4).
/// @param[in] train       n by 3F FP displacements of the training poses
/// @param[in] validation  the poses whose minimal entries are rebuilt to choose K (identities
///                        not in `train` if the dataset has them, else the training ones)
/// @param[in] minimal     the minimal table; entries whose pose `validation` lacks are skipped,
///                        FPs that `validation.fps` lacks are left out of an entry (an entry
///                        left with no FP is skipped)
/// Throws Error if train holds a NaN, its width is not 3F of validation.fps, no candidate can
/// be fit, or no minimal entry is usable.
CompletionModel fitCompletion(
    const Eigen::MatrixXd& train, const PoseSet& validation, const std::vector<MinimalPose>& minimal, const CompletionOptions& options);

/// Mean per-FP error (mm) of completing every usable minimal entry on every identity of `set`
/// with `mixture` (the criterion of fitCompletion). Throws Error if no entry is usable.
double minimalPoseError(const stats::Mppca& mixture, const PoseSet& set, const std::vector<MinimalPose>& minimal);

} // namespace facesketch::pose

#pragma once
// Mixtures of probabilistic principal component analysers fitted by EM: the density model of
// one face segment (thesis 4.2.1.3, 4.2.3) and of the concatenated segment latents (4.2.5).
// p(t) = sum_k pi_k N(t; mu_k, sigma_k^2 I + W_k W_k^T).
//
// This work is based on:
//   Tipping and Bishop, "Mixtures of probabilistic principal component analysers", Neural
//   Computation 11(2), 1999: the model, the E-step (eq. 21) and the M-step for pi_k and mu_k;
//   Tipping and Bishop 1999 (J. R. Statist. Soc. B, see stats/ppca.h): for fixed
//   responsibilities, the W_k and sigma_k^2 that maximise the expected log-likelihood are
//   the closed-form PPCA of the responsibility-weighted covariance S_k;
//   Gunnarsson, "Sketching 3D Faces", 2010, 4.2.1.1-4.2.1.4 and 4.2.3 (K-means start,
//   collapse guard, choosing the number of components by likelihood).
//
// Local maxima (thesis 4.2.1.3) are met with a few deterministic restarts (options.restarts).
//
// How it is computed. Each M-step fits every component exactly (closed-form weighted PPCA)
// instead of the single W-update of Tipping and Bishop's section 3.2, so each iteration is a
// full EM step and the log-likelihood cannot decrease. S_k, W_k and mu_k all lie in the span
// of the samples, so the whole fit runs on the n by n Gram matrix of the centred data:
// O(n^2 d) once for the Gram matrix, then O(K (n^2 q + s_k^3)) per iteration with s_k the
// samples of non-zero responsibility, independent of d. The d-dimensional W_k and mu_k are
// formed once at the end (O(K n d q)). When d >= n no S_k and no d by d matrix is ever
// formed; when d < n the M-step eigen-decomposes the d by d weighted covariance instead of
// the n by n weighted Gram matrix, the smaller of the two. Memory is O(n^2 + n d): meant for
// n up to a few thousand samples.
//
// Collapse guard (thesis 4.2.1.3): sigma_k^2 is bounded below by a floor; a component whose
// sigma_k^2 reaches the floor or whose responsibilities sum to less than minCount is reset to
// its initial state (its K-means cluster), and dropped after maxResets resets. A reset is
// the only step that may lower the log-likelihood; the fit records where it happened.

#include "stats/ppca.h"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace facesketch::stats {

struct Mppca {
    /// K components; all have the same dimension d.
    std::vector<Ppca> components;
    /// K mixing coefficients pi_k, positive, summing to 1.
    Eigen::VectorXd priors;

    Eigen::Index size() const { return static_cast<Eigen::Index>(components.size()); }
    Eigen::Index dim() const { return components.empty() ? 0 : components.front().dim(); }
};

struct MppcaOptions {
    /// Number of components K, 1 <= K <= n.
    int components = 3;
    /// Latent dimension q of every component, 1 <= q < d.
    int latentDim = 10;
    /// EM iterations at most; EM stops earlier when an iteration gains less than
    /// tolerance * |log-likelihood|.
    int maxIterations = 200;
    double tolerance = 1e-10;
    /// Floor on every sigma_k^2, relative to the mean per-coordinate variance of the data.
    double varianceFloor = 1e-6;
    /// A component whose responsibilities sum to less than this has lost its points.
    double minCount = 1.0;
    /// Resets allowed per component before it is dropped.
    int maxResets = 3;
    /// EM runs from different starts; the fit of highest likelihood is kept. Start 0 is the
    /// thesis' K-medoids seeding; start s > 0 seeds K-means with K-means++ drawn from seed s.
    /// Farthest-first seeding alone can put two seeds at the two ends of one elongated
    /// cluster, and EM on well-separated data then stays in that local maximum.
    int restarts = 4;
};

struct MppcaFit {
    Mppca model;
    /// n by K posterior responsibilities R_nk = p(k | t_n) of the final E-step; rows sum to 1.
    Eigen::MatrixXd responsibilities;
    /// K-means labels the kept fit started from (n), and which start it was.
    Eigen::VectorXi initialLabels;
    int start = 0;
    /// Total log-likelihood sum_n log p(t_n) of the training samples after every E-step, in
    /// nats. Non-decreasing except right after an iteration listed in resetIterations.
    std::vector<double> logLikelihood;
    /// Iterations (indices into logLikelihood) whose M-step reset or dropped a component.
    std::vector<int> resetIterations;
    /// Components dropped after too many resets (model.size() = options.components - dropped).
    int dropped = 0;
    int iterations = 0;
    bool converged = false;
};

/// Fits a mixture of PPCA by EM from K-means starts (stats/kmeans.h). Deterministic.
/// @param[in] X  n by d samples, one per row, n >= 2
/// Throws Error naming the row and column of a NaN or infinity in X, or an option out of range.
MppcaFit fitMppca(const Eigen::MatrixXd& X, const MppcaOptions& options);

/// m by K matrix of log(pi_k) + log N(t; mu_k, C_k) for every row t of T (Woodbury, q by q
/// only), in nats.
/// @param[in] T  m by d samples
Eigen::MatrixXd componentLogLikelihoods(const Mppca& model, const Eigen::MatrixXd& T);

/// log p(t) = log sum_k pi_k N(t; mu_k, C_k) for every row of T (log-sum-exp), m values.
Eigen::VectorXd logLikelihood(const Mppca& model, const Eigen::MatrixXd& T);

/// m by K responsibilities p(k | t) for every row of T; rows sum to 1.
Eigen::MatrixXd responsibilities(const Mppca& model, const Eigen::MatrixXd& T);

/// Choosing K (thesis 4.2.3). The thesis keeps the K of highest training likelihood, which
/// grows with K until every sample has its own component. A penalised likelihood (BIC) does
/// not help either: each component has about d (q + 1) parameters, far more than the n
/// samples when d >> n, so its large-sample approximation does not hold. We use what the face
/// model needs, the likelihood of faces not seen in training: F-fold cross-validation, the
/// folds drawn once from a seeded permutation and shared by every candidate.
struct ComponentScore {
    int components = 0;
    /// Mean held-out log-likelihood per sample, in nats (-infinity if a fold could not be fit).
    double heldOut = 0.0;
    /// Mean training log-likelihood per sample over the folds, in nats.
    double training = 0.0;
};

struct ComponentChoice {
    /// The candidate with the highest held-out likelihood (the earlier candidate on a tie).
    int best = 0;
    std::vector<ComponentScore> scores;
};

/// @param[in] X           n by d samples
/// @param[in] candidates  values of K to try, each in [1, n)
/// @param[in] options     everything but options.components is used for every fit
/// @param[in] folds       number of folds, 2 <= folds <= n
/// @param[in] seed        seed of the fold permutation
/// A candidate K that a fold cannot carry (more components than the fold's training samples,
/// or a degenerate component fit, stats/ppca.h DegenerateFit) scores -infinity; every other
/// Error propagates: a NaN in X, bad folds or candidates, options fitMppca rejects (latentDim
/// outside [1, d), restarts < 1), training samples of a fold all identical.
ComponentChoice chooseComponents(
    const Eigen::MatrixXd& X, const std::vector<int>& candidates, const MppcaOptions& options, int folds = 5, std::uint64_t seed = 1);

} // namespace facesketch::stats

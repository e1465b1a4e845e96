#include "stats/mppca.h"

#include "core/error.h"
#include "core/random.h"
#include "stats/check.h"
#include "stats/kmeans.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace facesketch::stats {

namespace {

using Indices = std::vector<Eigen::Index>;

// log N(x_j; mu, sigma^2 I + W W^T) for all n samples of the Gram matrix, with mu = X^T w and
// W = X^T B, through x_j - mu = X^T (e_j - w): O(n^2 q), never d-dimensional.
Eigen::VectorXd gramLogDensity(const Eigen::MatrixXd& G, const GramPpca& c, Eigen::Index d)
{
    const Eigen::Index q = c.B.cols();
    const Eigen::VectorXd Gw = G * c.weights;
    const double wGw = c.weights.dot(Gw);
    const Eigen::ArrayXd dist2 = ((G.diagonal() - 2.0 * Gw).array() + wGw).max(0.0);
    const Eigen::MatrixXd BtG = c.B.transpose() * G;
    const Eigen::MatrixXd Z = BtG.colwise() - c.B.transpose() * Gw; // q by n: W^T (x_j - mu)
    Eigen::MatrixXd M = BtG * c.B;                                  // W^T W
    M = 0.5 * (M + M.transpose()).eval();
    M.diagonal().array() += c.sigma2;
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    const Eigen::MatrixXd L = llt.matrixL().solve(Z);
    const Eigen::ArrayXd quad = ((dist2 - L.colwise().squaredNorm().transpose().array()) / c.sigma2).max(0.0);
    const double logDetC = static_cast<double>(d - q) * std::log(c.sigma2) + 2.0 * llt.matrixLLT().diagonal().array().log().sum();
    return -0.5 * (quad + static_cast<double>(d) * std::log(2.0 * std::numbers::pi) + logDetC);
}

// log sum_k exp(A(i, k)) for every row, shifted by the row maximum so nothing overflows.
Eigen::VectorXd logSumExpRows(const Eigen::MatrixXd& A)
{
    const Eigen::VectorXd top = A.rowwise().maxCoeff();
    return top.array() + (A.colwise() - top).array().exp().rowwise().sum().log();
}

struct GramFit {
    std::vector<GramPpca> components;
    Eigen::VectorXd priors;
    Eigen::MatrixXd logJoint; // n by K, log pi_k + log N(x_j; k) for every sample
    Eigen::MatrixXd responsibilities;
    Eigen::VectorXi initialLabels;
    std::vector<double> logLikelihood;
    std::vector<int> resetIterations;
    int dropped = 0;
    int iterations = 0;
    bool converged = false;
    int start = 0;
};

Eigen::MatrixXd logJointOf(const Eigen::MatrixXd& G, const std::vector<GramPpca>& components, const Eigen::VectorXd& priors, Eigen::Index d)
{
    Eigen::MatrixXd J(G.rows(), static_cast<Eigen::Index>(components.size()));
    for (size_t k = 0; k < components.size(); ++k) {
        const auto col = static_cast<Eigen::Index>(k);
        J.col(col) = gramLogDensity(G, components[k], d).array() + std::log(priors(col));
    }
    return J;
}

// EM on the samples listed in `train`, from a K-means labelling of them; the other rows of G
// only get log-densities (for held-out scoring) and zero responsibilities.
GramFit runEmFrom(const Eigen::MatrixXd& G, const Eigen::MatrixXd* factor, Eigen::Index d, const Indices& train, const MppcaOptions& o,
    const Eigen::VectorXi& labels, const GramPpca& global, double floor)
{
    const Eigen::Index n = G.rows();
    const auto nTrain = static_cast<Eigen::Index>(train.size());
    int K = o.components;
    const int q = o.latentDim;
    GramFit fit;
    fit.initialLabels = labels;

    // The initial state of each component, restored by the collapse guard: the PPCA of its
    // K-means cluster, or, for a cluster too small to carry q directions and noise, the
    // cluster mean with the subspace and noise of the whole data set.
    std::vector<GramPpca> initial;
    Eigen::VectorXd initialPriors(K);
    for (int k = 0; k < K; ++k) {
        Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
        for (Eigen::Index i = 0; i < nTrain; ++i)
            if (labels(i) == k)
                w(train[static_cast<size_t>(i)]) = 1.0;
        const double count = w.sum();
        w /= count;
        GramPpca c = fitPpcaGram(G, w, d, q, floor, factor);
        if (c.floored || count < o.minCount) {
            c.B = global.B;
            c.sigma2 = global.sigma2;
            c.floored = false;
        }
        initial.push_back(c);
        initialPriors(k) = count / static_cast<double>(nTrain);
    }
    fit.components = initial;
    fit.priors = initialPriors;
    std::vector<int> resets(static_cast<size_t>(K), 0);

    bool resetLast = false;
    for (int it = 0;; ++it) {
        // E-step.
        fit.logJoint = logJointOf(G, fit.components, fit.priors, d);
        const Eigen::VectorXd logP = logSumExpRows(fit.logJoint);
        fit.responsibilities = Eigen::MatrixXd::Zero(n, K);
        double total = 0.0;
        for (Eigen::Index i : train) {
            total += logP(i);
            fit.responsibilities.row(i) = (fit.logJoint.row(i).array() - logP(i)).exp();
        }
        fit.logLikelihood.push_back(total);
        if (it > 0 && !resetLast) {
            const double previous = fit.logLikelihood[static_cast<size_t>(it - 1)];
            if (total - previous <= o.tolerance * std::abs(total)) {
                fit.converged = true;
                break;
            }
        }
        if (it == o.maxIterations)
            break;

        // M-step: every component is refit exactly for the new responsibilities.
        resetLast = false;
        std::vector<int> collapsed;
        for (int k = 0; k < K; ++k) {
            const Eigen::VectorXd r = fit.responsibilities.col(k);
            const double count = r.sum();
            fit.priors(k) = count / static_cast<double>(nTrain);
            if (count < o.minCount) {
                collapsed.push_back(k);
                continue;
            }
            fit.components[static_cast<size_t>(k)] = fitPpcaGram(G, r / count, d, q, floor, factor);
            if (fit.components[static_cast<size_t>(k)].floored)
                collapsed.push_back(k);
        }
        // Collapse guard, from the last index down so erasing keeps the others valid.
        for (auto at = collapsed.rbegin(); at != collapsed.rend(); ++at) {
            const auto k = static_cast<size_t>(*at);
            resetLast = true;
            if (++resets[k] > o.maxResets && K > 1) {
                fit.components.erase(fit.components.begin() + *at);
                initial.erase(initial.begin() + *at);
                resets.erase(resets.begin() + *at);
                const Eigen::VectorXd keep = fit.priors;
                const Eigen::VectorXd keepInitial = initialPriors;
                fit.priors.resize(K - 1);
                initialPriors.resize(K - 1);
                fit.priors << keep.head(*at), keep.tail(K - 1 - *at);
                initialPriors << keepInitial.head(*at), keepInitial.tail(K - 1 - *at);
                --K;
                ++fit.dropped;
            } else {
                fit.components[k] = initial[k];
                fit.priors(*at) = initialPriors(*at);
            }
        }
        if (resetLast) {
            fit.priors /= fit.priors.sum();
            fit.resetIterations.push_back(it);
        }
        fit.iterations = it + 1;
    }
    return fit;
}

// Validates the options, then runs EM from every start of options.restarts and keeps the fit
// of highest training likelihood (the earliest on a tie). factor: the centred samples when
// d < n (see fitPpcaGram), else null.
GramFit runEm(const Eigen::MatrixXd& G, const Eigen::MatrixXd* factor, Eigen::Index d, const Indices& train, const MppcaOptions& o)
{
    const Eigen::Index n = G.rows();
    const auto nTrain = static_cast<Eigen::Index>(train.size());
    if (o.components < 1 || o.components > nTrain)
        fail("fitMppca: components = ", o.components, " outside [1, ", nTrain, "]");
    if (o.latentDim < 1 || o.latentDim >= d)
        fail("fitMppca: latentDim = ", o.latentDim, " outside [1, d) with d = ", d);
    if (o.restarts < 1)
        fail("fitMppca: restarts = ", o.restarts, ", need at least 1");

    Eigen::VectorXd uniform = Eigen::VectorXd::Zero(n);
    uniform(train).setConstant(1.0 / static_cast<double>(nTrain));
    const double meanVariance = (uniform.dot(G.diagonal()) - uniform.dot(G * uniform)) / static_cast<double>(d);
    if (!(meanVariance > 0.0))
        fail("fitMppca: the ", nTrain, " training samples are all identical");
    const double floor = o.varianceFloor * meanVariance;
    const GramPpca global = fitPpcaGram(G, uniform, d, o.latentDim, floor, factor);
    const Eigen::MatrixXd Gtrain = G(train, train);

    GramFit best;
    for (int start = 0; start < o.restarts; ++start) {
        KMeansOptions km;
        km.seeding = start == 0 ? Seeding::KMedoids : Seeding::KMeansPlusPlus;
        km.seed = static_cast<std::uint64_t>(start);
        const Eigen::VectorXi labels = kmeansGram(Gtrain, o.components, km).labels;
        GramFit fit = runEmFrom(G, factor, d, train, o, labels, global, floor);
        fit.start = start;
        if (start == 0 || fit.logLikelihood.back() > best.logLikelihood.back())
            best = std::move(fit);
    }
    return best;
}

} // namespace

MppcaFit fitMppca(const Eigen::MatrixXd& X, const MppcaOptions& options)
{
    requireFinite(X, "fitMppca: X");
    if (X.rows() < 2)
        fail("fitMppca: ", X.rows(), " samples, need at least 2");
    const Eigen::Index n = X.rows();
    const Eigen::VectorXd centre = X.colwise().mean().transpose();
    const Eigen::MatrixXd Xc = X.rowwise() - centre.transpose();
    const Eigen::MatrixXd G = centredGram(X);
    Indices all(static_cast<size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i)
        all[static_cast<size_t>(i)] = i;

    GramFit gram = runEm(G, X.cols() < n ? &Xc : nullptr, X.cols(), all, options);
    MppcaFit fit;
    for (const GramPpca& c : gram.components)
        fit.model.components.push_back(materialise(Xc, centre, c));
    fit.model.priors = gram.priors;
    fit.responsibilities = gram.responsibilities;
    fit.initialLabels = gram.initialLabels;
    fit.logLikelihood = gram.logLikelihood;
    fit.resetIterations = gram.resetIterations;
    fit.dropped = gram.dropped;
    fit.iterations = gram.iterations;
    fit.converged = gram.converged;
    fit.start = gram.start;
    return fit;
}

Eigen::MatrixXd componentLogLikelihoods(const Mppca& model, const Eigen::MatrixXd& T)
{
    if (model.size() == 0 || model.priors.size() != model.size())
        fail("componentLogLikelihoods: the model has ", model.size(), " components and ", model.priors.size(), " priors");
    Eigen::MatrixXd J(T.rows(), model.size());
    for (Eigen::Index k = 0; k < model.size(); ++k)
        J.col(k) = logLikelihood(model.components[static_cast<size_t>(k)], T).array() + std::log(model.priors(k));
    return J;
}

Eigen::VectorXd logLikelihood(const Mppca& model, const Eigen::MatrixXd& T)
{
    return logSumExpRows(componentLogLikelihoods(model, T));
}

Eigen::MatrixXd responsibilities(const Mppca& model, const Eigen::MatrixXd& T)
{
    const Eigen::MatrixXd J = componentLogLikelihoods(model, T);
    return (J.colwise() - logSumExpRows(J)).array().exp();
}

ComponentChoice chooseComponents(
    const Eigen::MatrixXd& X, const std::vector<int>& candidates, const MppcaOptions& options, int folds, std::uint64_t seed)
{
    requireFinite(X, "chooseComponents: X");
    const Eigen::Index n = X.rows();
    if (folds < 2 || folds > n)
        fail("chooseComponents: folds = ", folds, " outside [2, ", n, "]");
    if (candidates.empty())
        fail("chooseComponents: no candidate numbers of components");
    const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
    const Eigen::MatrixXd G = Xc * Xc.transpose();
    const Eigen::MatrixXd* factor = X.cols() < n ? &Xc : nullptr;
    Random random(seed);
    const std::vector<int> order = random.permutation(static_cast<int>(n));
    std::vector<Indices> train(static_cast<size_t>(folds)), test(static_cast<size_t>(folds));
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto fold = static_cast<size_t>(i % folds);
        const Eigen::Index sample = order[static_cast<size_t>(i)];
        for (size_t f = 0; f < train.size(); ++f)
            (f == fold ? test[f] : train[f]).push_back(sample);
    }
    for (size_t f = 0; f < train.size(); ++f)
        std::sort(train[f].begin(), train[f].end());

    ComponentChoice choice;
    double bestScore = -std::numeric_limits<double>::infinity();
    for (int K : candidates) {
        if (K < 1 || K >= n)
            fail("chooseComponents: candidate K = ", K, " outside [1, ", n, ")");
        MppcaOptions o = options;
        o.components = K;
        ComponentScore score { K, 0.0, 0.0 };
        for (size_t f = 0; f < train.size(); ++f) {
            // K is not viable on this fold if the fold has fewer samples than components, or
            // if a component's fit is degenerate (an empty cluster). Anything else (bad
            // options, identical samples) is the caller's to see, so only these two are skipped.
            if (static_cast<size_t>(K) > train[f].size()) {
                score.heldOut = -std::numeric_limits<double>::infinity();
                continue;
            }
            try {
                const GramFit fit = runEm(G, factor, X.cols(), train[f], o);
                const Eigen::VectorXd logP = logSumExpRows(fit.logJoint);
                for (Eigen::Index i : test[f])
                    score.heldOut += logP(i);
                score.training += fit.logLikelihood.back() / static_cast<double>(train[f].size());
            } catch (const DegenerateFit&) {
                score.heldOut = -std::numeric_limits<double>::infinity();
            }
        }
        score.heldOut /= static_cast<double>(n);
        score.training /= static_cast<double>(folds);
        if (score.heldOut > bestScore || choice.scores.empty()) {
            bestScore = score.heldOut;
            choice.best = K;
        }
        choice.scores.push_back(score);
    }
    return choice;
}

} // namespace facesketch::stats

// Tests of stats/mppca: EM's monotonicity, the Gram-matrix E-step against dense densities,
// recovery of a known mixture (d < n and d >> n), the collapse guard, and choosing K.
#include "stats/mppca.h"

#include "core/error.h"
#include "synthetic.h"

#include <catch2/catch.hpp>
#include <limits>
#include <set>
#include <sstream>

using namespace facesketch;
using namespace facesketch::stats;
using namespace facesketch::test;

namespace {

// K components in d dimensions whose means are meanScale * N(0, I) apart, q-dimensional
// loadings of about one unit per coordinate and noise sigma^2.
Mppca knownMixture(Random& random, Eigen::Index d, int K, int q, double meanScale, double sigma2)
{
    Mppca model;
    for (int k = 0; k < K; ++k)
        model.components.push_back(randomPpca(random, d, q, meanScale, 1.0, sigma2));
    model.priors = Eigen::VectorXd::LinSpaced(K, 1.0, 1.5);
    model.priors /= model.priors.sum();
    return model;
}

// For every true component, the fitted component with the nearest mean; each used once.
std::vector<int> matchComponents(const Mppca& truth, const Mppca& fitted)
{
    std::vector<int> match;
    for (const Ppca& t : truth.components) {
        int best = -1;
        double bestDistance = std::numeric_limits<double>::infinity();
        for (int k = 0; k < fitted.size(); ++k) {
            const double distance = (fitted.components[static_cast<size_t>(k)].mean - t.mean).norm();
            if (distance < bestDistance) {
                bestDistance = distance;
                best = k;
            }
        }
        match.push_back(best);
    }
    return match;
}

void checkRecovery(
    const Mppca& truth, const MppcaFit& fit, double meanTolerance, double angleTolerance, double sigmaTolerance, double priorTolerance)
{
    REQUIRE(fit.model.size() == truth.size());
    const std::vector<int> match = matchComponents(truth, fit.model);
    REQUIRE(std::set<int>(match.begin(), match.end()).size() == match.size());
    for (size_t k = 0; k < match.size(); ++k) {
        const Ppca& t = truth.components[k];
        const Ppca& f = fit.model.components[static_cast<size_t>(match[k])];
        INFO("component " << k);
        // Mean error relative to the spread of the component around its mean.
        const double spread = std::sqrt((t.W * t.W.transpose()).trace() + t.dim() * t.sigma2);
        CHECK((f.mean - t.mean).norm() < meanTolerance * spread);
        CHECK(largestPrincipalAngle(f.W, t.W) < angleTolerance);
        CHECK(relativeDifference(f.sigma2, t.sigma2) < sigmaTolerance);
        CHECK(std::abs(fit.model.priors(match[k]) - truth.priors(static_cast<Eigen::Index>(k))) < priorTolerance);
    }
}

} // namespace

TEST_CASE("mppca: EM never lowers the likelihood")
{
    // Overlapping components, so that EM takes many soft steps: once with d < n (M-step
    // through the data factor), once with d >> n (M-step through the Gram matrix).
    for (const auto& [d, n, K, q, meanScale] : { std::tuple { 12, 300, 4, 2, 0.7 }, std::tuple { 200, 80, 3, 3, 0.15 } }) {
        Random random(21);
        Mppca truth;
        for (int k = 0; k < K; ++k)
            truth.components.push_back(randomPpca(random, d, q, meanScale, 1.0, 0.5));
        truth.priors = Eigen::VectorXd::Constant(K, 1.0 / K);
        Eigen::VectorXi labels;
        const Eigen::MatrixXd X = sampleMixture(random, truth, n, labels);
        MppcaOptions options;
        options.components = K;
        options.latentDim = q;
        options.restarts = 1;
        const MppcaFit fit = fitMppca(X, options);
        INFO("d = " << d << ", n = " << n << ", iterations " << fit.iterations);
        REQUIRE(fit.resetIterations.empty());
        REQUIRE(fit.iterations >= 7);
        for (size_t i = 1; i < fit.logLikelihood.size(); ++i)
            CHECK(fit.logLikelihood[i] >= fit.logLikelihood[i - 1] - 1e-12 * std::abs(fit.logLikelihood[i]));
        CHECK(fit.logLikelihood.back() > fit.logLikelihood.front() + 100.0);
    }
}

TEST_CASE("mppca: the Gram-matrix E-step equals the dense densities of the fitted model")
{
    Random random(22);
    const Mppca truth = knownMixture(random, 40, 3, 3, 3.0, 0.3);
    Eigen::VectorXi labels;
    const Eigen::MatrixXd X = sampleMixture(random, truth, 90, labels);
    MppcaOptions options;
    options.components = 3;
    options.latentDim = 3;
    const MppcaFit fit = fitMppca(X, options);

    // The recorded likelihood and responsibilities come from the Gram matrix; recompute both
    // from the d-dimensional model with full covariances.
    double total = 0.0;
    Eigen::MatrixXd R(X.rows(), fit.model.size());
    for (Eigen::Index i = 0; i < X.rows(); ++i) {
        Eigen::VectorXd joint(fit.model.size());
        for (Eigen::Index k = 0; k < fit.model.size(); ++k) {
            const Ppca& c = fit.model.components[static_cast<size_t>(k)];
            joint(k) = std::log(fit.model.priors(k)) + denseLogDensity(X.row(i).transpose(), c.mean, denseCovariance(c));
        }
        const double top = joint.maxCoeff();
        const double logP = top + std::log((joint.array() - top).exp().sum());
        total += logP;
        R.row(i) = (joint.array() - logP).exp().transpose();
    }
    CHECK(relativeDifference(fit.logLikelihood.back(), total) < 1e-9);
    CHECK((fit.responsibilities - R).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((fit.responsibilities.rowwise().sum().array() - 1.0).abs().maxCoeff() < 1e-12);
    // And the public evaluation functions agree.
    CHECK(relativeDifference(logLikelihood(fit.model, X).sum(), total) < 1e-9);
    CHECK((responsibilities(fit.model, X) - R).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("mppca: one component is PPCA")
{
    Random random(23);
    const Eigen::MatrixXd X = random.normalMatrix(40, 70) * 2.0;
    MppcaOptions options;
    options.components = 1;
    options.latentDim = 5;
    const MppcaFit fit = fitMppca(X, options);
    const Ppca ppca = fitPpca(X, 5);
    const Ppca& c = fit.model.components.front();
    CHECK(relativeDifference(c.sigma2, ppca.sigma2) < 1e-9);
    CHECK(relativeDifference(c.W * c.W.transpose(), ppca.W * ppca.W.transpose()) < 1e-9);
    CHECK(relativeDifference(c.mean, ppca.mean) < 1e-12);
}

TEST_CASE("mppca: EM recovers the components of a known mixture")
{
    Random random(24);
    const Mppca truth = knownMixture(random, 30, 3, 2, 4.0, 0.25);
    Eigen::VectorXi labels;
    const Eigen::MatrixXd X = sampleMixture(random, truth, 450, labels);
    MppcaOptions options;
    options.components = 3;
    options.latentDim = 2;
    const MppcaFit fit = fitMppca(X, options);
    REQUIRE(fit.converged);
    // About 150 samples per component: means to within ~1/sqrt(150) of the spread, the
    // subspace to a few degrees; sigma^2 rests on ~28 x 150 residual degrees of freedom
    // (2% standard error) and is biased low by about (q + 1) / n_k = 2%.
    checkRecovery(truth, fit, 0.15, 0.15, 0.08, 0.06);
}

TEST_CASE("mppca: EM recovers the components when d >> n")
{
    Random random(25);
    const Mppca truth = knownMixture(random, 900, 2, 2, 1.0, 0.25);
    Eigen::VectorXi labels;
    const Eigen::MatrixXd X = sampleMixture(random, truth, 120, labels);
    MppcaOptions options;
    options.components = 2;
    options.latentDim = 2;
    const MppcaFit fit = fitMppca(X, options);
    REQUIRE(fit.converged);
    // Every sample goes to the component that drew it.
    const std::vector<int> match = matchComponents(truth, fit.model);
    for (Eigen::Index i = 0; i < X.rows(); ++i)
        REQUIRE(fit.responsibilities(i, match[static_cast<size_t>(labels(i))]) > 0.999);
    // The means and subspaces rest on ~60 samples each. The maximum-likelihood sigma^2 is
    // biased low by about (q + 1) / n_k = 5% here: the q leading directions of a sample
    // covariance also soak up noise, and S divides by n_k.
    checkRecovery(truth, fit, 0.2, 0.3, 0.1, 0.15);
}

TEST_CASE("mppca: the collapse guard keeps a degenerate fit finite")
{
    Random random(26);
    // One broad cloud plus three copies of one far point: K-means gives the copies a cluster
    // of their own, whose PPCA has no variance left for the noise.
    Eigen::MatrixXd X(63, 10);
    X.topRows(60) = random.normalMatrix(60, 10);
    X.bottomRows(3).rowwise() = Eigen::RowVectorXd::Constant(10, 50.0);
    MppcaOptions options;
    options.components = 3;
    options.latentDim = 2;
    const MppcaFit fit = fitMppca(X, options);
    CHECK((!fit.resetIterations.empty() || fit.dropped > 0));
    CHECK(fit.model.size() == 3 - fit.dropped);
    for (const Ppca& c : fit.model.components) {
        CHECK(std::isfinite(c.sigma2));
        CHECK(c.sigma2 > 0.0);
        CHECK(c.W.allFinite());
    }
    CHECK(std::isfinite(fit.logLikelihood.back()));
    CHECK(fit.responsibilities.allFinite());
}

TEST_CASE("mppca: held-out likelihood picks the true number of components")
{
    Random random(27);
    const Mppca truth = knownMixture(random, 20, 3, 2, 3.0, 0.3);
    Eigen::VectorXi labels;
    const Eigen::MatrixXd X = sampleMixture(random, truth, 150, labels);
    MppcaOptions options;
    options.latentDim = 2;
    const ComponentChoice choice = chooseComponents(X, { 1, 2, 3, 4 }, options, 3, 1);
    REQUIRE(choice.scores.size() == 4);
    std::ostringstream table;
    for (const ComponentScore& s : choice.scores)
        table << "K = " << s.components << ": held-out " << s.heldOut << ", training " << s.training << "\n";
    INFO(table.str());
    CHECK(choice.best == 3);
    // The training likelihood keeps growing with K; the held-out one does not.
    CHECK(choice.scores[3].training > choice.scores[2].training);
    CHECK(choice.scores[2].heldOut > choice.scores[1].heldOut);
}

TEST_CASE("mppca: deterministic, and rejects NaN and bad options")
{
    Random random(28);
    Eigen::MatrixXd X = random.normalMatrix(50, 8);
    X.topRows(25).array() += 10.0;
    MppcaOptions options;
    options.components = 2;
    options.latentDim = 2;
    const MppcaFit a = fitMppca(X, options), b = fitMppca(X, options);
    REQUIRE(a.model.size() == 2);
    REQUIRE(a.logLikelihood == b.logLikelihood);
    REQUIRE(a.model.components[1].W == b.model.components[1].W);

    Eigen::MatrixXd bad = X;
    bad(4, 1) = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(fitMppca(bad, options), Catch::Contains("X(4, 1)"));
    options.latentDim = 8;
    REQUIRE_THROWS_AS(fitMppca(X, options), Error);
    options.latentDim = 2;
    options.components = 51;
    REQUIRE_THROWS_AS(fitMppca(X, options), Error);
}

TEST_CASE("mppca: choosing K skips a K a fold cannot carry and lets bad input through")
{
    Random random(29);
    Eigen::MatrixXd X = random.normalMatrix(30, 8);
    X.topRows(15).array() += 10.0;
    MppcaOptions options;
    options.latentDim = 2;
    // 3 folds of 30 samples train on 20: K = 25 is a valid candidate (< n) that no fold can fit.
    const ComponentChoice choice = chooseComponents(X, { 1, 2, 25 }, options, 3, 1);
    REQUIRE(choice.scores.size() == 3);
    CHECK(choice.scores[2].heldOut == -std::numeric_limits<double>::infinity());
    CHECK(choice.scores[2].training == 0.0);
    CHECK(std::isfinite(choice.scores[0].heldOut));
    CHECK(std::isfinite(choice.scores[1].heldOut));
    CHECK(choice.best == (choice.scores[1].heldOut > choice.scores[0].heldOut ? 2 : 1));

    // Options the fit rejects are the caller's error, not an unviable K.
    options.latentDim = 8;
    REQUIRE_THROWS_WITH(chooseComponents(X, { 1, 2 }, options, 3, 1), Catch::Contains("latentDim = 8"));
    options.latentDim = 2;
    options.restarts = 0;
    REQUIRE_THROWS_WITH(chooseComponents(X, { 1, 2 }, options, 3, 1), Catch::Contains("restarts = 0"));
    options.restarts = 1;
    // Identical samples fit no K at all.
    const Eigen::MatrixXd same = Eigen::MatrixXd::Ones(30, 8);
    REQUIRE_THROWS_WITH(chooseComponents(same, { 1, 2 }, options, 3, 1), Catch::Contains("all identical"));
    Eigen::MatrixXd bad = X;
    bad(7, 3) = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(chooseComponents(bad, { 1, 2 }, options, 3, 1), Catch::Contains("X(7, 3)"));
}

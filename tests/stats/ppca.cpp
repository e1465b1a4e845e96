// Tests of stats/ppca: dual and primal fits agree, the fit is the textbook maximum-likelihood
// solution, and the Woodbury-based evaluations match dense formulas.
#include "stats/ppca.h"

#include "core/error.h"
#include "synthetic.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using namespace facesketch;
using namespace facesketch::stats;
using namespace facesketch::test;

TEST_CASE("ppca: dual PPCA equals PPCA in subspace and sigma^2")
{
    Random random(1);
    for (const auto& [n, d, q] : { std::tuple { 30, 80, 4 }, std::tuple { 60, 20, 3 }, std::tuple { 12, 200, 10 } }) {
        const Ppca truth = randomPpca(random, d, q, 5.0, 1.0, 0.3);
        Eigen::VectorXi labels;
        Mppca one;
        one.components = { truth };
        one.priors = Eigen::VectorXd::Ones(1);
        const Eigen::MatrixXd X = sampleMixture(random, one, n, labels);
        const Ppca primal = fitPpcaPrimal(X, q);
        const Ppca dual = fitPpcaDual(X, q);
        INFO("n = " << n << ", d = " << d << ", q = " << q);
        CHECK(relativeDifference(dual.sigma2, primal.sigma2) < 1e-9);
        CHECK(relativeDifference(dual.mean, primal.mean) < 1e-12);
        // W is unique up to the sign of each column; W W^T is not.
        CHECK(relativeDifference(dual.W * dual.W.transpose(), primal.W * primal.W.transpose()) < 1e-9);
        CHECK(largestPrincipalAngle(dual.W, primal.W) < 1e-6);
    }
}

TEST_CASE("ppca: the fit is Tipping and Bishop's closed form")
{
    Random random(2);
    const int n = 50, d = 15, q = 4;
    const Eigen::MatrixXd X = random.normalMatrix(n, d) * random.normalMatrix(d, d);
    const Ppca model = fitPpca(X, q);

    // Independently: singular values of the centred data give the eigenvalues of S.
    const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
    const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(Xc / std::sqrt(double(n))).singularValues();
    const Eigen::VectorXd lambda = s.cwiseProduct(s);
    const double sigma2 = lambda.tail(d - q).sum() / (d - q);
    CHECK(relativeDifference(model.sigma2, sigma2) < 1e-10);
    // W^T W = L_q - sigma^2 I, diagonal.
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(q, q);
    expected.diagonal() = lambda.head(q).array() - sigma2;
    CHECK(relativeDifference(model.W.transpose() * model.W, expected) < 1e-9);

    // It is a maximum: moving sigma^2 or scaling W only lowers the likelihood.
    const double best = logLikelihood(model, X).sum();
    for (double factor : { 0.9, 0.99, 1.01, 1.1 }) {
        Ppca moved = model;
        moved.sigma2 *= factor;
        CHECK(logLikelihood(moved, X).sum() < best);
        moved = model;
        moved.W *= factor;
        CHECK(logLikelihood(moved, X).sum() < best);
    }
}

TEST_CASE("ppca: log-likelihood matches the dense Gaussian density")
{
    Random random(3);
    const Ppca model = randomPpca(random, 30, 5, 2.0, 1.5, 0.2);
    const Eigen::MatrixXd T = random.normalMatrix(6, 30) * 3.0;
    const Eigen::VectorXd fast = logLikelihood(model, T);
    const Eigen::MatrixXd C = denseCovariance(model);
    for (Eigen::Index i = 0; i < T.rows(); ++i)
        CHECK(relativeDifference(fast(i), denseLogDensity(T.row(i).transpose(), model.mean, C)) < 1e-9);
}

TEST_CASE("ppca: latent is the posterior mean and clean-up the projection onto the subspace")
{
    Random random(4);
    const Ppca model = randomPpca(random, 24, 4, 2.0, 1.0, 0.5);
    const Eigen::MatrixXd T = random.normalMatrix(5, 24) * 2.0;
    const Eigen::MatrixXd Z = latent(model, T);
    REQUIRE(Z.rows() == 5);
    REQUIRE(Z.cols() == 4);
    // E[x | t] = W^T C^{-1} (t - mu) by Bayes' theorem on the joint Gaussian of x and t.
    const Eigen::MatrixXd C = denseCovariance(model);
    const Eigen::MatrixXd E = (T.rowwise() - model.mean.transpose()).transpose();
    const Eigen::MatrixXd expected = (model.W.transpose() * C.llt().solve(E)).transpose();
    CHECK(relativeDifference(Z, expected) < 1e-9);

    // Clean-up: mu + W (W^T W)^{-1} W^T (t - mu), an idempotent orthogonal projection.
    const Eigen::MatrixXd clean = cleanUp(model, T);
    const Eigen::MatrixXd WtW = model.W.transpose() * model.W;
    const Eigen::MatrixXd projected = (model.W * WtW.llt().solve(model.W.transpose() * E)).colwise() + model.mean;
    CHECK(relativeDifference(clean, projected.transpose()) < 1e-9);
    CHECK(relativeDifference(cleanUp(model, clean), clean) < 1e-9);
    const Eigen::MatrixXd residual = (T - clean) * model.W;
    CHECK(residual.cwiseAbs().maxCoeff() < 1e-9 * T.cwiseAbs().maxCoeff() * model.W.cwiseAbs().maxCoeff() * 24);
}

TEST_CASE("ppca: rejects NaN and a latent dimension out of range")
{
    Random random(5);
    Eigen::MatrixXd X = random.normalMatrix(10, 6);
    REQUIRE_THROWS_AS(fitPpca(X, 0), Error);
    REQUIRE_THROWS_AS(fitPpca(X, 6), Error);
    X(3, 4) = std::numeric_limits<double>::infinity();
    REQUIRE_THROWS_WITH(fitPpca(X, 2), Catch::Contains("X(3, 4)"));
    const Ppca model = randomPpca(random, 6, 2, 1.0, 1.0, 1.0);
    REQUIRE_THROWS_WITH(logLikelihood(model, X), Catch::Contains("(3, 4)"));
    REQUIRE_THROWS_AS(logLikelihood(model, Eigen::MatrixXd::Zero(2, 5)), Error);
}

TEST_CASE("ppca: a Gram fit with no weighted sample is a degenerate fit, a bad q is not")
{
    Random random(6);
    const Eigen::MatrixXd X = random.normalMatrix(10, 6);
    const Eigen::MatrixXd G = X * X.transpose();
    REQUIRE_THROWS_AS(fitPpcaGram(G, Eigen::VectorXd::Zero(10), 6, 2), DegenerateFit);
    REQUIRE_THROWS_WITH(fitPpcaGram(G, Eigen::VectorXd::Zero(10), 6, 2), Catch::Contains("all weights are zero"));
    try {
        fitPpcaGram(G, Eigen::VectorXd::Constant(10, 0.1), 6, 6);
        FAIL("q = d was accepted");
    } catch (const DegenerateFit&) {
        FAIL("q = d was reported as a degenerate fit");
    } catch (const Error& e) {
        CHECK(std::string(e.what()).find("latent dimension q = 6") != std::string::npos);
    }
}

TEST_CASE("ppca: dimensionHolding counts the principal directions that hold a fraction of the variance")
{
    // Eight samples along three orthogonal directions with variances 100, 10 and 1: the
    // coefficients are columns 1-3 of the 8 by 8 Sylvester-Hadamard matrix (entries +-1, zero
    // mean, mutually orthogonal), so the sample covariance's eigenvalues are exactly 100, 10, 1
    // (times 8/8) and the shares 100/111 = 0.901, 110/111 = 0.991 and 1.
    const auto hadamard = [](int i, int j) { return std::popcount(static_cast<unsigned>(i & j)) % 2 ? -1.0 : 1.0; };
    Random random(7);
    for (int d : { 4, 40 }) { // the covariance route and the Gram route
        INFO("d = " << d);
        const Eigen::MatrixXd Q
            = Eigen::HouseholderQR<Eigen::MatrixXd>(random.normalMatrix(d, 3)).householderQ() * Eigen::MatrixXd::Identity(d, 3);
        Eigen::MatrixXd X(8, d);
        for (int i = 0; i < 8; ++i)
            X.row(i)
                = (10.0 * hadamard(i, 1) * Q.col(0) + std::sqrt(10.0) * hadamard(i, 2) * Q.col(1) + hadamard(i, 3) * Q.col(2)).transpose()
                + Eigen::RowVectorXd::Constant(d, 5.0); // an offset the centring removes
        CHECK(dimensionHolding(X, 0.9) == 1);
        CHECK(dimensionHolding(X, 0.902) == 2);
        CHECK(dimensionHolding(X, 0.99) == 2);
        CHECK(dimensionHolding(X, 0.992) == 3);
        CHECK(dimensionHolding(X, 1.0) == 3);
        CHECK(dimensionHolding(Eigen::MatrixXd::Constant(8, d, 2.0), 0.5) == 0); // no variance
    }
    Eigen::MatrixXd X = random.normalMatrix(10, 6);
    REQUIRE_THROWS_WITH(dimensionHolding(X, 0.0), Catch::Contains("fraction 0 is not in (0, 1]"));
    REQUIRE_THROWS_WITH(dimensionHolding(X, 1.5), Catch::Contains("fraction 1.5"));
    REQUIRE_THROWS_AS(dimensionHolding(X.topRows(1), 0.5), Error);
    X(2, 5) = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(dimensionHolding(X, 0.5), Catch::Contains("X(2, 5)"));
}

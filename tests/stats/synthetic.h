#pragma once
// Test data for the statistics tests: random PPCA models and mixtures, samples drawn from
// them, and dense textbook reference computations (full d by d covariances; small d only).

#include "core/random.h"
#include "stats/mppca.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <numbers>

namespace facesketch::test {

/// A PPCA with a random mean of scale meanScale, loadings of about `scale` per coordinate.
inline stats::Ppca randomPpca(Random& random, Eigen::Index d, int q, double meanScale, double scale, double sigma2)
{
    stats::Ppca p;
    p.mean = meanScale * random.normalMatrix(d, 1);
    p.W = scale * random.normalMatrix(d, q);
    p.sigma2 = sigma2;
    return p;
}

/// n samples (rows) from the mixture; labels(i) is the component that drew sample i.
inline Eigen::MatrixXd sampleMixture(Random& random, const stats::Mppca& model, Eigen::Index n, Eigen::VectorXi& labels)
{
    const Eigen::Index d = model.dim();
    Eigen::MatrixXd X(n, d);
    labels.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        double u = random.uniform();
        Eigen::Index k = 0;
        while (k + 1 < model.size() && u >= model.priors(k)) {
            u -= model.priors(k);
            ++k;
        }
        const stats::Ppca& c = model.components[static_cast<size_t>(k)];
        X.row(i) = (c.mean + c.W * random.normalMatrix(c.latentDim(), 1) + std::sqrt(c.sigma2) * random.normalMatrix(d, 1)).transpose();
        labels(i) = static_cast<int>(k);
    }
    return X;
}

/// The full covariance sigma^2 I + W W^T.
inline Eigen::MatrixXd denseCovariance(const stats::Ppca& p)
{
    Eigen::MatrixXd C = p.W * p.W.transpose();
    C.diagonal().array() += p.sigma2;
    return C;
}

/// log N(x; mean, C) through a Cholesky factor of the dense C.
inline double denseLogDensity(const Eigen::VectorXd& x, const Eigen::VectorXd& mean, const Eigen::MatrixXd& C)
{
    const Eigen::LLT<Eigen::MatrixXd> llt(C);
    const Eigen::VectorXd e = llt.matrixL().solve(x - mean);
    const double logDet = 2.0 * llt.matrixLLT().diagonal().array().log().sum();
    return -0.5 * (static_cast<double>(x.size()) * std::log(2.0 * std::numbers::pi) + logDet + e.squaredNorm());
}

/// Largest principal angle between the column spans of A and B (same column count), radians.
inline double largestPrincipalAngle(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B)
{
    const Eigen::MatrixXd Qa = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ() * Eigen::MatrixXd::Identity(A.rows(), A.cols());
    const Eigen::MatrixXd Qb = Eigen::HouseholderQR<Eigen::MatrixXd>(B).householderQ() * Eigen::MatrixXd::Identity(B.rows(), B.cols());
    const Eigen::VectorXd cosines = Eigen::JacobiSVD<Eigen::MatrixXd>(Qa.transpose() * Qb).singularValues();
    return std::acos(std::min(1.0, cosines.minCoeff()));
}

/// |a - b| / max(|a|, |b|, tiny): the relative difference the tests compare against 1e-9.
inline double relativeDifference(double a, double b)
{
    return std::abs(a - b) / std::max({ std::abs(a), std::abs(b), 1e-300 });
}

/// max |A - B| / max |B|.
inline double relativeDifference(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B)
{
    return (A - B).cwiseAbs().maxCoeff() / std::max(B.cwiseAbs().maxCoeff(), 1e-300);
}

} // namespace facesketch::test

#include "stats/ppca.h"

#include "core/error.h"
#include "stats/check.h"
#include "stats/kmeans.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>
#include <numbers>
#include <vector>

namespace facesketch::stats {

namespace {

void checkShape(const Eigen::MatrixXd& X, int q, const char* who)
{
    requireFinite(X, who);
    if (X.rows() < 2)
        fail(who, ": ", X.rows(), " samples, need at least 2");
    if (q < 1 || q >= X.cols())
        fail(who, ": latent dimension q = ", q, " outside [1, d) with d = ", X.cols());
}

void checkModel(const Ppca& model, Eigen::Index cols, const char* who)
{
    if (cols != model.dim())
        fail(who, ": samples have ", cols, " columns, the model has dimension ", model.dim());
    if (!(model.sigma2 > 0.0))
        fail(who, ": the model's sigma^2 = ", model.sigma2, " is not positive");
}

} // namespace

GramPpca fitPpcaGram(
    const Eigen::MatrixXd& G, const Eigen::VectorXd& weights, Eigen::Index d, int q, double sigma2Floor, const Eigen::MatrixXd* factor)
{
    const Eigen::Index n = G.rows();
    if (q < 1 || q >= d)
        fail("fitPpcaGram: latent dimension q = ", q, " outside [1, d) with d = ", d);
    std::vector<Eigen::Index> support;
    for (Eigen::Index i = 0; i < n; ++i)
        if (weights(i) > 0.0)
            support.push_back(i);
    const auto s = static_cast<Eigen::Index>(support.size());
    if (s == 0)
        throw DegenerateFit("fitPpcaGram: all weights are zero");

    // Rows of zero weight add nothing to S, so working on the support only is exact.
    const Eigen::VectorXd w = weights(support);
    const Eigen::VectorXd root = w.cwiseSqrt();
    // The q leading eigenpairs of Y Y^T (s by s), Y = D^1/2 (X_s - 1 m^T), whose non-zero
    // eigenvalues are those of S = Y^T Y. With a factor narrower than the support, through
    // the smaller Y^T Y instead: u = Y v / sqrt(lambda).
    GramPpca fit;
    fit.weights = weights;
    fit.eigenvalues = Eigen::VectorXd::Zero(q);
    Eigen::MatrixXd U = Eigen::MatrixXd::Zero(s, q);
    double total = 0.0;
    if (factor != nullptr && factor->cols() < s) {
        const Eigen::MatrixXd Fs = (*factor)(support, Eigen::all);
        const Eigen::RowVectorXd m = w.transpose() * Fs;
        const Eigen::MatrixXd Y = root.asDiagonal() * (Fs.rowwise() - m);
        const Eigen::MatrixXd K = Y.transpose() * Y;
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K);
        if (eig.info() != Eigen::Success)
            throw DegenerateFit(cat("fitPpcaGram: eigen-decomposition of the ", K.rows(), " by ", K.rows(), " covariance failed"));
        const Eigen::Index r = K.rows();
        for (Eigen::Index j = 0; j < std::min<Eigen::Index>(q, r); ++j) {
            fit.eigenvalues(j) = std::max(0.0, eig.eigenvalues()(r - 1 - j));
            if (fit.eigenvalues(j) > 0.0)
                U.col(j) = Y * eig.eigenvectors().col(r - 1 - j) / std::sqrt(fit.eigenvalues(j));
        }
        total = K.trace();
    } else {
        // H: the Gram matrix of the support about its weighted mean.
        const Eigen::MatrixXd Gs = G(support, support);
        const Eigen::VectorXd Gw = Gs * w;
        const double wGw = w.dot(Gw);
        Eigen::MatrixXd H = Gs;
        H.colwise() -= Gw;
        H.rowwise() -= Gw.transpose();
        H.array() += wGw;
        const Eigen::MatrixXd K = root.asDiagonal() * H * root.asDiagonal();
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K);
        if (eig.info() != Eigen::Success)
            throw DegenerateFit(cat("fitPpcaGram: eigen-decomposition of the ", s, " by ", s, " Gram matrix failed"));
        for (Eigen::Index j = 0; j < std::min<Eigen::Index>(q, s); ++j) {
            fit.eigenvalues(j) = std::max(0.0, eig.eigenvalues()(s - 1 - j));
            U.col(j) = eig.eigenvectors().col(s - 1 - j);
        }
        total = K.trace();
    }
    fit.sigma2 = std::max(0.0, total - fit.eigenvalues.sum()) / static_cast<double>(d - q);
    if (fit.sigma2 < sigma2Floor) {
        fit.sigma2 = sigma2Floor;
        fit.floored = true;
    }

    // W = Y^T A with column j of A = u_j sqrt((l_j - sigma^2) / l_j); zero if l_j <= sigma^2.
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(s, q);
    for (int j = 0; j < q; ++j) {
        const double l = fit.eigenvalues(j);
        if (l > fit.sigma2)
            A.col(j) = U.col(j) * std::sqrt((l - fit.sigma2) / l);
    }
    // Y^T = X_s^T (I - w 1^T) D^1/2, so B = (I - w 1^T) D^1/2 A.
    const Eigen::MatrixXd DA = root.asDiagonal() * A;
    const Eigen::RowVectorXd colSum = DA.colwise().sum();
    fit.B = Eigen::MatrixXd::Zero(n, q);
    fit.B(support, Eigen::all) = DA - w * colSum;
    return fit;
}

Ppca materialise(const Eigen::MatrixXd& Xc, const Eigen::VectorXd& centre, const GramPpca& fit)
{
    Ppca model;
    model.mean = centre + Xc.transpose() * fit.weights;
    model.W = Xc.transpose() * fit.B;
    model.sigma2 = fit.sigma2;
    return model;
}

Ppca fitPpcaPrimal(const Eigen::MatrixXd& X, int q)
{
    checkShape(X, q, "fitPpcaPrimal: X");
    const Eigen::Index n = X.rows();
    const Eigen::Index d = X.cols();
    Ppca model;
    model.mean = X.colwise().mean().transpose();
    const Eigen::MatrixXd Xc = X.rowwise() - model.mean.transpose();
    const Eigen::MatrixXd S = Xc.transpose() * Xc / static_cast<double>(n);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
    if (eig.info() != Eigen::Success)
        fail("fitPpcaPrimal: eigen-decomposition of the ", d, " by ", d, " covariance failed");
    double top = 0.0;
    for (int j = 0; j < q; ++j)
        top += std::max(0.0, eig.eigenvalues()(d - 1 - j));
    model.sigma2 = std::max(0.0, S.trace() - top) / static_cast<double>(d - q);
    model.W = Eigen::MatrixXd::Zero(d, q);
    for (int j = 0; j < q; ++j) {
        const double l = eig.eigenvalues()(d - 1 - j);
        if (l > model.sigma2)
            model.W.col(j) = eig.eigenvectors().col(d - 1 - j) * std::sqrt(l - model.sigma2);
    }
    return model;
}

Ppca fitPpcaDual(const Eigen::MatrixXd& X, int q)
{
    checkShape(X, q, "fitPpcaDual: X");
    const Eigen::Index n = X.rows();
    const Eigen::VectorXd centre = X.colwise().mean().transpose();
    const Eigen::MatrixXd Xc = X.rowwise() - centre.transpose();
    const Eigen::VectorXd uniform = Eigen::VectorXd::Constant(n, 1.0 / static_cast<double>(n));
    return materialise(Xc, centre, fitPpcaGram(centredGram(X), uniform, X.cols(), q));
}

Ppca fitPpca(const Eigen::MatrixXd& X, int q)
{
    return X.cols() > X.rows() ? fitPpcaDual(X, q) : fitPpcaPrimal(X, q);
}

int dimensionHolding(const Eigen::MatrixXd& X, double fraction)
{
    if (!(fraction > 0 && fraction <= 1))
        fail("dimensionHolding: fraction ", fraction, " is not in (0, 1]");
    if (X.rows() < 2)
        fail("dimensionHolding: ", X.rows(), " samples; at least 2 are needed");
    requireFinite(X, "dimensionHolding: X");
    // The non-zero eigenvalues of X_c^T X_c and X_c X_c^T are the same.
    Eigen::MatrixXd G;
    if (X.cols() > X.rows())
        G = centredGram(X);
    else {
        const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
        G = Xc.transpose() * Xc;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G, Eigen::EigenvaluesOnly);
    if (eig.info() != Eigen::Success)
        fail("dimensionHolding: the eigen-decomposition did not converge");
    const Eigen::VectorXd values = eig.eigenvalues().reverse().cwiseMax(0.0); // decreasing
    const double total = values.sum();
    if (total <= 0)
        return 0;
    // The relative slack keeps rounding from counting the zero eigenvalues past the rank at 1.
    const double wanted = fraction * total * (1 - 1e-12);
    double held = 0;
    int q = 0;
    while (q < values.size() && held < wanted)
        held += values(q++);
    return q;
}

Eigen::MatrixXd latent(const Ppca& model, const Eigen::MatrixXd& T)
{
    checkModel(model, T.cols(), "latent");
    requireFinite(T, "latent: T");
    Eigen::MatrixXd M = model.W.transpose() * model.W;
    M.diagonal().array() += model.sigma2;
    const Eigen::MatrixXd E = T.rowwise() - model.mean.transpose();
    return M.llt().solve(model.W.transpose() * E.transpose()).transpose();
}

Eigen::MatrixXd fromLatent(const Ppca& model, const Eigen::MatrixXd& Z)
{
    if (Z.cols() != model.latentDim())
        fail("fromLatent: latent vectors have ", Z.cols(), " columns, the model has q = ", model.latentDim());
    requireFinite(Z, "fromLatent: Z");
    const Eigen::MatrixXd WtW = model.W.transpose() * model.W;
    Eigen::MatrixXd M = WtW;
    M.diagonal().array() += model.sigma2;
    // A pseudo-inverse because zero columns of W (eigenvalues below sigma^2) make W^T W singular.
    const Eigen::MatrixXd coefficients = WtW.completeOrthogonalDecomposition().pseudoInverse() * M;
    Eigen::MatrixXd out = (model.W * (coefficients * Z.transpose())).transpose();
    out.rowwise() += model.mean.transpose();
    return out;
}

Eigen::MatrixXd cleanUp(const Ppca& model, const Eigen::MatrixXd& T)
{
    return fromLatent(model, latent(model, T));
}

Eigen::VectorXd logLikelihood(const Ppca& model, const Eigen::MatrixXd& T)
{
    checkModel(model, T.cols(), "logLikelihood");
    requireFinite(T, "logLikelihood: T");
    const auto d = static_cast<double>(model.dim());
    const auto q = static_cast<double>(model.latentDim());
    Eigen::MatrixXd M = model.W.transpose() * model.W;
    M.diagonal().array() += model.sigma2;
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    // |C| = sigma^{2(d-q)} |M| (determinant lemma); C^{-1} = (I - W M^{-1} W^T) / sigma^2.
    const double logDetC = (d - q) * std::log(model.sigma2) + 2.0 * llt.matrixLLT().diagonal().array().log().sum();
    const Eigen::MatrixXd E = T.rowwise() - model.mean.transpose();
    const Eigen::MatrixXd Z = model.W.transpose() * E.transpose();
    const Eigen::MatrixXd L = llt.matrixL().solve(Z);
    const Eigen::VectorXd quad = (E.rowwise().squaredNorm() - L.colwise().squaredNorm().transpose()) / model.sigma2;
    return -0.5 * (quad.array() + d * std::log(2.0 * std::numbers::pi) + logDetC);
}

} // namespace facesketch::stats

#include "stats/conditional.h"

#include "core/error.h"
#include "stats/check.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <numbers>

namespace facesketch::stats {

namespace {
double checkedNoise(double noiseVariance, const char* where, Eigen::Index vertex)
{
    if (!std::isfinite(noiseVariance) || noiseVariance < 0.0)
        fail(where, ": the noise variance ", noiseVariance, " of vertex ", vertex, " is not a finite value >= 0");
    return noiseVariance;
}

// The o-vector that stacks rowsOf(block) (a vector of block.rows values) over the measurement
// blocks in order: values, noise variances and residuals are all laid out this way.
template <class Blocks, class RowsOf> Eigen::VectorXd stackRows(const Blocks& blocks, Eigen::Index size, RowsOf rowsOf)
{
    Eigen::VectorXd out(size);
    Eigen::Index row = 0;
    for (const auto& b : blocks) {
        out.segment(row, b.rows) = rowsOf(b);
        row += b.rows;
    }
    return out;
}
} // namespace

void Observations::addVertex(Eigen::Index vertex, const Eigen::Vector3d& xyz, double noiseVariance)
{
    if (vertex < 0)
        fail("Observations::addVertex: vertex ", vertex, " is negative");
    requireFinite(xyz, "Observations::addVertex: xyz");
    Block b;
    b.first = 3 * vertex;
    b.width = 3;
    b.rows = 3;
    b.P = Eigen::Matrix3d::Identity();
    b.identity = true;
    b.y = xyz;
    b.noise.setConstant(checkedNoise(noiseVariance, "Observations::addVertex", vertex));
    blocks_.push_back(b);
    size_ += 3;
}

void Observations::addProjectedVertex(
    Eigen::Index vertex, const Eigen::Matrix<double, 2, 3>& P, const Eigen::Vector2d& image, double noiseVariance)
{
    addProjectedVertex(vertex, P, image, Eigen::Vector2d::Constant(noiseVariance));
}

void Observations::addProjectedVertex(
    Eigen::Index vertex, const Eigen::Matrix<double, 2, 3>& P, const Eigen::Vector2d& image, const Eigen::Vector2d& noiseVariances)
{
    if (vertex < 0)
        fail("Observations::addProjectedVertex: vertex ", vertex, " is negative");
    requireFinite(P, "Observations::addProjectedVertex: P");
    requireFinite(image, "Observations::addProjectedVertex: image");
    const double error = (P * P.transpose() - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff();
    if (error > 1e-9)
        fail("Observations::addProjectedVertex: the rows of P for vertex ", vertex, " are not orthonormal (|P P^T - I| = ", error, ")");
    Block b;
    b.first = 3 * vertex;
    b.width = 3;
    b.rows = 2;
    b.P.topRows<2>() = P;
    b.y.head<2>() = image;
    b.noise.head<2>() << checkedNoise(noiseVariances[0], "Observations::addProjectedVertex", vertex),
        checkedNoise(noiseVariances[1], "Observations::addProjectedVertex", vertex);
    blocks_.push_back(b);
    size_ += 2;
}

void Observations::addVertexAlong(Eigen::Index vertex, const Eigen::Vector3d& direction, double value, double noiseVariance)
{
    if (vertex < 0)
        fail("Observations::addVertexAlong: vertex ", vertex, " is negative");
    requireFinite(direction, "Observations::addVertexAlong: direction");
    if (!std::isfinite(value))
        fail("Observations::addVertexAlong: value ", value, " of vertex ", vertex, " is not finite");
    if (std::abs(direction.norm() - 1.0) > 1e-9)
        fail("Observations::addVertexAlong: the direction for vertex ", vertex, " has length ", direction.norm(), ", not 1");
    Block b;
    b.first = 3 * vertex;
    b.width = 3;
    b.rows = 1;
    b.P.row(0) = direction.transpose();
    b.y(0) = value;
    b.noise[0] = checkedNoise(noiseVariance, "Observations::addVertexAlong", vertex);
    blocks_.push_back(b);
    size_ += 1;
}

void Observations::addVertexRows(
    Eigen::Index vertex, const Eigen::Matrix3d& R, int rows, const Eigen::Vector3d& values, const Eigen::Vector3d& noiseVariances)
{
    if (vertex < 0)
        fail("Observations::addVertexRows: vertex ", vertex, " is negative");
    if (rows < 1 || rows > 3)
        fail("Observations::addVertexRows: ", rows, " rows for vertex ", vertex, " (1 to 3)");
    const Eigen::MatrixXd used = R.topRows(rows);
    requireFinite(used, "Observations::addVertexRows: R");
    requireFinite(Eigen::VectorXd(values.head(rows)), "Observations::addVertexRows: values");
    const double error = (used * used.transpose() - Eigen::MatrixXd::Identity(rows, rows)).cwiseAbs().maxCoeff();
    if (error > 1e-9)
        fail("Observations::addVertexRows: the rows for vertex ", vertex, " are not orthonormal (|R R^T - I| = ", error, ")");
    Block b;
    b.first = 3 * vertex;
    b.width = 3;
    b.rows = rows;
    b.P.topRows(rows) = used;
    b.y.head(rows) = values.head(rows);
    for (int i = 0; i < rows; ++i)
        b.noise[i] = checkedNoise(noiseVariances[i], "Observations::addVertexRows", vertex);
    blocks_.push_back(b);
    size_ += rows;
}

bool Observations::noisy() const
{
    for (const Block& b : blocks_)
        if ((b.noise.head(b.rows).array() > 0.0).any())
            return true;
    return false;
}

Eigen::VectorXd Observations::noiseVariances() const
{
    return stackRows(blocks_, size_, [](const Block& b) { return b.noise.head(b.rows); });
}

void Observations::addCoordinate(Eigen::Index index, double value)
{
    if (index < 0)
        fail("Observations::addCoordinate: index ", index, " is negative");
    if (!std::isfinite(value))
        fail("Observations::addCoordinate: value ", value, " at index ", index, " is not finite");
    Block b;
    b.first = index;
    b.width = 1;
    b.rows = 1;
    b.P(0, 0) = 1.0;
    b.y(0) = value;
    blocks_.push_back(b);
    size_ += 1;
}

Observations Observations::restrict(const std::vector<int>& local) const
{
    Observations out;
    for (const Block& b : blocks_) {
        const Eigen::Index vertex = b.first / 3;
        if (vertex >= static_cast<Eigen::Index>(local.size()) || local[static_cast<size_t>(vertex)] < 0)
            continue;
        Block moved = b;
        moved.first = 3 * static_cast<Eigen::Index>(local[static_cast<size_t>(vertex)]) + b.first % 3;
        out.blocks_.push_back(moved);
        out.size_ += b.rows;
    }
    return out;
}

void Observations::validate(Eigen::Index d) const
{
    std::vector<bool> seen(static_cast<size_t>(d), false);
    for (const Block& b : blocks_) {
        if (b.first + b.width > d)
            fail("Observations: coordinates ", b.first, "..", b.first + b.width - 1, " lie outside a vector of dimension ", d);
        for (Eigen::Index i = b.first; i < b.first + b.width; ++i) {
            if (seen[static_cast<size_t>(i)])
                fail("Observations: coordinate ", i, " (vertex ", i / 3, ") is measured twice");
            seen[static_cast<size_t>(i)] = true;
        }
    }
}

Eigen::MatrixXd Observations::denseP(Eigen::Index d) const
{
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(size_, d);
    Eigen::Index row = 0;
    for (const Block& b : blocks_) {
        P.block(row, b.first, b.rows, b.width) = b.P.topLeftCorner(b.rows, b.width);
        row += b.rows;
    }
    return P;
}

Eigen::VectorXd Observations::values() const
{
    return stackRows(blocks_, size_, [](const Block& b) { return b.y.head(b.rows); });
}

Eigen::VectorXd Observations::residual(const Eigen::VectorXd& a) const
{
    return stackRows(blocks_, size_, [&a](const Block& b) -> Eigen::VectorXd {
        return b.y.head(b.rows) - b.P.topLeftCorner(b.rows, b.width) * a.segment(b.first, b.width);
    });
}

Eigen::MatrixXd Observations::apply(const Eigen::MatrixXd& A) const
{
    // Fixed-size cases: a face has thousands of tiny blocks, and dynamic-size products on
    // 3 by 3 blocks spend most of their time on size checks.
    Eigen::MatrixXd PA(size_, A.cols());
    Eigen::Index row = 0;
    for (const Block& b : blocks_) {
        if (b.width == 1)
            PA.row(row) = A.row(b.first);
        else if (b.identity)
            PA.middleRows<3>(row) = A.middleRows<3>(b.first);
        else if (b.rows == 3)
            PA.middleRows<3>(row).noalias() = b.P * A.middleRows<3>(b.first);
        else if (b.rows == 1)
            PA.row(row).noalias() = b.P.row(0) * A.middleRows<3>(b.first);
        else
            PA.middleRows<2>(row).noalias() = b.P.topRows<2>() * A.middleRows<3>(b.first);
        row += b.rows;
    }
    return PA;
}

void Observations::addTransposed(const Eigen::VectorXd& v, Eigen::VectorXd& a) const
{
    Eigen::Index row = 0;
    for (const Block& b : blocks_) {
        a.segment(b.first, b.width) += b.P.topLeftCorner(b.rows, b.width).transpose() * v.segment(row, b.rows);
        row += b.rows;
    }
}

void Observations::pinMeasured(Eigen::VectorXd& a) const
{
    for (const Block& b : blocks_)
        if (b.identity || b.width == 1) // addVertex, addCoordinate (as apply() tells them)
            for (int i = 0; i < b.rows; ++i)
                if (b.noise(i) == 0.0)
                    a(b.first + i) = b.y(i);
}

ComponentPosterior condition(const Ppca& model, const Observations& observations)
{
    observations.validate(model.dim());
    if (!(model.sigma2 > 0.0))
        fail("condition: the model's sigma^2 = ", model.sigma2, " is not positive");
    const auto o = static_cast<double>(observations.size());
    const auto q = static_cast<double>(model.latentDim());
    const Eigen::MatrixXd WO = observations.apply(model.W);
    const Eigen::VectorXd r = observations.residual(model.mean);
    if (observations.noisy()) {
        // y ~ N(P mu, D + W_O W_O^T), D = diag(sigma^2 + noise): the same algebra with D^-1
        // weighting every row (Bishop 2006, 12.2.1 with a diagonal noise).
        const Eigen::VectorXd D = observations.noiseVariances().array() + model.sigma2;
        const Eigen::VectorXd Dinv = D.cwiseInverse();
        Eigen::MatrixXd M = Eigen::MatrixXd::Identity(model.latentDim(), model.latentDim());
        M.selfadjointView<Eigen::Lower>().rankUpdate((Dinv.cwiseSqrt().asDiagonal() * WO).transpose());
        const Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(M);
        const Eigen::VectorXd Wr = WO.transpose() * Dinv.cwiseProduct(r);
        ComponentPosterior post;
        post.latent = llt.solve(Wr);
        const double explained = llt.matrixL().solve(Wr).squaredNorm();
        const double quad = std::max(0.0, r.cwiseProduct(Dinv).dot(r) - explained);
        const double logDet = D.array().log().sum() + 2.0 * llt.matrixLLT().diagonal().array().log().sum();
        post.logLikelihood = -0.5 * (o * std::log(2.0 * std::numbers::pi) + logDet + quad);
        return post;
    }
    // Only the lower triangle of M = sigma^2 I + W_O^T W_O is formed; the LLT reads no more.
    Eigen::MatrixXd M = Eigen::MatrixXd::Identity(model.latentDim(), model.latentDim()) * model.sigma2;
    M.selfadjointView<Eigen::Lower>().rankUpdate(WO.transpose());
    const Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(M);
    const Eigen::VectorXd Wr = WO.transpose() * r;

    ComponentPosterior post;
    post.latent = llt.solve(Wr);
    // r^T W_O M^{-1} W_O^T r = |L^{-1} W_O^T r|^2 keeps the quadratic form symmetric in rounding.
    const double explained = llt.matrixL().solve(Wr).squaredNorm();
    const double quad = std::max(0.0, r.squaredNorm() - explained) / model.sigma2;
    // |sigma^2 I_o + W_O W_O^T| = sigma^{2(o - q)} |M_O| holds for o < q as well.
    const double logDet = (o - q) * std::log(model.sigma2) + 2.0 * llt.matrixLLT().diagonal().array().log().sum();
    post.logLikelihood = -0.5 * (o * std::log(2.0 * std::numbers::pi) + logDet + quad);
    return post;
}

Eigen::VectorXd conditionalMean(const Ppca& model, const Observations& observations, const ComponentPosterior& posterior)
{
    Eigen::VectorXd t = model.mean + model.W * posterior.latent;
    Eigen::VectorXd unexplained = observations.residual(t);
    if (observations.noisy())
        unexplained.array() *= model.sigma2 / (observations.noiseVariances().array() + model.sigma2);
    observations.addTransposed(unexplained, t);
    observations.pinMeasured(t);
    return t;
}

Inference inferComponents(const Mppca& model, const Observations& observations)
{
    const Eigen::Index K = model.size();
    if (K == 0 || model.priors.size() != K)
        fail("infer: the model has ", K, " components and ", model.priors.size(), " priors");
    Inference result;
    Eigen::VectorXd scores(K);
    for (Eigen::Index k = 0; k < K; ++k) {
        ComponentPosterior post = condition(model.components[static_cast<size_t>(k)], observations);
        post.logPrior = std::log(model.priors(k));
        scores(k) = post.score();
        result.components.push_back(post);
    }
    Eigen::Index winner = 0;
    const double top = scores.maxCoeff(&winner);
    result.winner = static_cast<int>(winner);
    result.posterior = (scores.array() - top).exp();
    result.posterior /= result.posterior.sum();
    return result;
}

Inference infer(const Mppca& model, const Observations& observations)
{
    Inference result = inferComponents(model, observations);
    const auto winner = static_cast<size_t>(result.winner);
    result.reconstruction = conditionalMean(model.components[winner], observations, result.components[winner]);
    return result;
}

} // namespace facesketch::stats

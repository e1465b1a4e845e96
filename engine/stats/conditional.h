#pragma once
// Conditional inference of missing data under a mixture of PPCA (thesis 4.2.1.6): given a
// few measurements of a face (vertex positions, or their 2D images in a view), the most
// probable component and the expected whole face under it.
//
// This work is based on:
//   Gunnarsson, "Sketching 3D Faces", 2010, eqs. 4.16 and 4.21 (component score and the
//   partitioned-Gaussian conditional mean);
//   Tipping and Bishop, "Mixtures of probabilistic principal component analysers", 1999
//   (the model, C = sigma^2 I + W W^T);
//   Bishop, "Pattern Recognition and Machine Learning", 2006, section 2.3.3 (linear-Gaussian
//   model: Bayes' theorem for y = P t).
//
// The maths. Measurements are y = P t for a matrix P whose rows are orthonormal and whose
// blocks each touch one vertex (3 coordinates) or one coordinate. Because P P^T = I, under a
// component y ~ N(P mu, sigma^2 I + W_O W_O^T) with W_O = P W, still a PPCA. With
// M_O = sigma^2 I + W_O^T W_O (q by q) and r = y - P mu:
//   latent posterior mean   z = M_O^{-1} W_O^T r
//   conditional mean        E[t | y] = mu + W z + P^T (r - W_O z)
//   marginal log-likelihood log N(y) = -1/2 (o log 2 pi + (o - q) log sigma^2 + log|M_O|
//                                            + (|r|^2 - r^T W_O M_O^{-1} W_O^T r) / sigma^2).
// A coordinate no measurement touches gets mu_M + W_M z, thesis eq. 4.21 rewritten by the
// Woodbury identity; a vertex seen in full gets its measured position back; a vertex seen in
// a 2D view keeps its measured image and takes its depth from the model. Cost O(o q^2 + d q)
// per component: never an o by o or d by d matrix.
//
// Conventions: a face is a vector t of d = 3 #V coordinates, vertex v at t(3v .. 3v+2) as
// x, y, z (millimetres). A 2D view is given by the first two rows of the camera rotation:
// y = R_xy t_v for an orthographic camera (any translation already removed from y).

#include "stats/mppca.h"
#include "stats/ppca.h"

#include <Eigen/Core>
#include <vector>

namespace facesketch::stats {

/// Measurements of one vector. A coordinate may be measured once only: two measurements
/// of the same coordinate would see the same noise twice, which the model cannot express.
///
/// Every vertex measurement may carry a noise variance (squared units, mm^2 for faces, per
/// measured row, default 0): the measurement is then y = P t + e with e ~ N(0, noise I), on top
/// of the model's own sigma^2. A noisy measurement pulls the face towards it by its weight
/// instead of pinning it (condition() and conditionalMean() below); with every noise 0 the
/// maths is exactly the noiseless one of this file's header.
class Observations {
public:
    /// The full position of vertex v: t(3v .. 3v+2) = xyz.
    void addVertex(Eigen::Index vertex, const Eigen::Vector3d& xyz, double noiseVariance = 0.0);

    /// The image of vertex v in a view: P t(3v .. 3v+2) = image. P is 2 by 3 with orthonormal
    /// rows (|P P^T - I| <= 1e-9), e.g. the x and y rows of a rotation.
    void addProjectedVertex(
        Eigen::Index vertex, const Eigen::Matrix<double, 2, 3>& P, const Eigen::Vector2d& image, double noiseVariance = 0.0);
    /// The same with a noise variance per row of P (e.g. a drawn line's position across it
    /// known well, along it poorly).
    void addProjectedVertex(
        Eigen::Index vertex, const Eigen::Matrix<double, 2, 3>& P, const Eigen::Vector2d& image, const Eigen::Vector2d& noiseVariances);

    /// One direction of vertex v: d . t(3v .. 3v+2) = value, d a unit vector (|d| - 1 within
    /// 1e-9), e.g. the direction across a drawn line in its view plane.
    void addVertexAlong(Eigen::Index vertex, const Eigen::Vector3d& direction, double value, double noiseVariance = 0.0);

    /// The first `rows` (1 to 3) rows of R measure vertex v: R t(3v .. 3v+2) = values, each row
    /// with its own noise variance. The rows must be orthonormal (|R R^T - I| <= 1e-9 over
    /// them), e.g. a view's x and y rows and its axis, for a position known well in the image
    /// and poorly in depth.
    void addVertexRows(
        Eigen::Index vertex, const Eigen::Matrix3d& R, int rows, const Eigen::Vector3d& values, const Eigen::Vector3d& noiseVariances);

    /// One coordinate: t(index) = value (for vectors that are not faces, e.g. the latent
    /// vectors of the segment correlation, thesis 4.2.5).
    void addCoordinate(Eigen::Index index, double value);

    /// Number of scalar measurements o (3 per vertex, 2 per projected vertex, 1 per coordinate).
    Eigen::Index size() const { return size_; }
    /// Whether any measurement has a noise variance above 0.
    bool noisy() const;
    /// The noise variance of every scalar measurement, o values (0 for coordinates).
    Eigen::VectorXd noiseVariances() const;
    bool empty() const { return blocks_.empty(); }

    /// The measurements of the vertices v with local[v] >= 0, renumbered so that vertex v
    /// becomes vertex local[v] (a single-coordinate measurement moves with its vertex, 3v..3v+2).
    /// Measurements of other vertices, or beyond local.size(), are left out. For taking the
    /// part of a face's measurements that falls in one segment.
    Observations restrict(const std::vector<int>& local) const;

    /// Throws Error if a measurement lies outside a d-dimensional vector or two measure the
    /// same coordinate.
    void validate(Eigen::Index d) const;

    /// The dense o by d matrix P and the o measurements y, for tests and small problems.
    Eigen::MatrixXd denseP(Eigen::Index d) const;
    Eigen::VectorXd values() const;

    /// y - P a, o values, for any d vector a.
    Eigen::VectorXd residual(const Eigen::VectorXd& a) const;
    /// P A for a d by q matrix A: o by q.
    Eigen::MatrixXd apply(const Eigen::MatrixXd& A) const;
    /// Adds P^T b (b has o values) to the d vector a.
    void addTransposed(const Eigen::VectorXd& b, Eigen::VectorXd& a) const;
    /// Sets each coordinate of a that a noise-free measurement gives whole (addVertex,
    /// addCoordinate) to that measurement. a + (y - a) can miss y by a rounding (where a and y
    /// differ in sign or by more than a factor of two), and a measured coordinate is known.
    void pinMeasured(Eigen::VectorXd& a) const;

private:
    struct Block {
        Eigen::Index first = 0;                          // first coordinate touched
        int width = 0;                                   // coordinates touched: 1 or 3
        int rows = 0;                                    // measurements: 1, 2 or 3 (1 of a vertex: a direction)
        Eigen::Matrix3d P = Eigen::Matrix3d::Zero();     // rows by width used
        Eigen::Vector3d y = Eigen::Vector3d::Zero();     // rows used
        Eigen::Vector3d noise = Eigen::Vector3d::Zero(); // variance of each row's measurement
        bool identity = false;                           // P is I (addVertex): products skip it
    };
    std::vector<Block> blocks_;
    Eigen::Index size_ = 0;
};

/// What the measurements say under one component.
struct ComponentPosterior {
    /// q posterior mean of the latent variables, M_O^{-1} W_O^T (y - P mu).
    Eigen::VectorXd latent;
    /// log N(y; P mu, sigma^2 I + W_O W_O^T), nats.
    double logLikelihood = 0.0;
    /// log pi_k (0 for a single PPCA).
    double logPrior = 0.0;
    /// Thesis eq. 4.16 in logarithms: log p(y | k) + log pi_k.
    double score() const { return logLikelihood + logPrior; }
};

/// Conditions one PPCA on the measurements. Throws Error if they do not fit its dimension.
/// With noisy measurements (Observations::noisy) the covariance of y is D + W_O W_O^T with
/// D = diag(sigma^2 + noise_i): M = I + W_O^T D^-1 W_O, latent M^-1 W_O^T D^-1 r, and
/// log|D + W_O W_O^T| = log|D| + log|M| (still O(o q^2)).
ComponentPosterior condition(const Ppca& model, const Observations& observations);

/// E[t | y] under one PPCA (d values), from the posterior computed by condition(). A measured
/// coordinate with noise n gets mu + W z plus sigma^2 / (sigma^2 + n) of the measurement's
/// residual (all of it when n = 0: the measurement itself).
Eigen::VectorXd conditionalMean(const Ppca& model, const Observations& observations, const ComponentPosterior& posterior);

struct Inference {
    /// Component with the highest score (the lowest index on a tie).
    int winner = 0;
    /// d values: E[t | y, winner], the whole vector with the missing part filled in.
    Eigen::VectorXd reconstruction;
    /// K posteriors, one per component.
    std::vector<ComponentPosterior> components;
    /// K probabilities p(k | y), summing to 1.
    Eigen::VectorXd posterior;
};

/// Conditions every component of the mixture and reconstructs under the winner. With no
/// measurements the winner is the component of highest prior and the result its mean.
Inference infer(const Mppca& model, const Observations& observations);

/// infer() without the reconstruction (left empty): every component conditioned, the winner
/// and p(k | y). For callers that need the winner's conditional mean on a few coordinates only
/// (stats::reconstructAt), not all d of them.
Inference inferComponents(const Mppca& model, const Observations& observations);

} // namespace facesketch::stats

#pragma once
// Probabilistic principal component analysis: one linear-Gaussian model of a d-dimensional
// vector, t = W x + mu + e with x ~ N(0, I_q) and e ~ N(0, sigma^2 I_d), so that
// t ~ N(mu, C) with C = sigma^2 I + W W^T. The building block of the mixtures
// (stats/mppca.h), the segment clean-up (thesis 4.2.4) and the segment correlation (4.2.5).
//
// This work is based on:
//   Tipping and Bishop, "Probabilistic principal component analysis", J. R. Statist. Soc. B
//   61(3), 1999: the closed-form maximum-likelihood fit (eqs. 7-8), the posterior of x;
//   Lawrence, "Probabilistic non-linear principal component analysis with Gaussian process
//   latent variable models", JMLR 6, 2005: the dual route through the n by n Gram matrix;
//   Gunnarsson, "Sketching 3D Faces", 2010, sections 4.2.1.2 and 4.2.1.5 (eqs. 4.17-4.20).
//
// Conventions: samples are rows of an n by d matrix; S = 1/n sum (t_n - mu)(t_n - mu)^T is
// the maximum-likelihood covariance (divided by n, not n - 1); W = U_q (L_q - sigma^2 I)^{1/2}
// with the rotation R = I, so the columns of W are orthogonal and sorted by decreasing
// length; sigma^2 is the mean of the d - q discarded eigenvalues of S, counting the zero ones
// when d > n. A column whose eigenvalue does not exceed sigma^2 is zero.
// Nothing here forms a d by d matrix except fitPpcaPrimal, the textbook reference.

#include "core/error.h"

#include <Eigen/Core>

namespace facesketch::stats {

/// A component that cannot be fit from the samples it was given: no sample has a positive
/// weight (a mixture's cluster came out empty), or the eigen-decomposition did not converge.
/// Not a fault of the caller's data as a whole; a caller trying several numbers of mixture
/// components (chooseComponents, stats/mppca.h) skips the candidate that met it.
class DegenerateFit : public Error {
public:
    using Error::Error;
};

/// A fitted PPCA model. Owns its arrays; copying is cheap next to a fit.
struct Ppca {
    /// d mean vector mu.
    Eigen::VectorXd mean;
    /// d by q factor loadings W.
    Eigen::MatrixXd W;
    /// Isotropic noise variance sigma^2 > 0, in squared data units (mm^2 for faces).
    double sigma2 = 1.0;

    Eigen::Index dim() const { return mean.size(); }
    Eigen::Index latentDim() const { return W.cols(); }
};

/// PPCA of a weighted covariance, given through the Gram matrix of the samples. The model it
/// describes has mean = X^T weights and W = X^T B for the rows X of the samples that G was
/// built from (centred or not: B's columns sum to zero).
struct GramPpca {
    /// n sample weights, non-negative, summing to 1.
    Eigen::VectorXd weights;
    /// n by q coefficients of W in terms of the samples; zero rows where the weight is zero.
    Eigen::MatrixXd B;
    /// Noise variance, at least the floor passed to the fit.
    double sigma2 = 1.0;
    /// q leading eigenvalues of the weighted covariance S, decreasing (zeros past its rank).
    Eigen::VectorXd eigenvalues;
    /// True if sigma^2 was raised to the floor: the data left almost nothing for the noise.
    bool floored = false;
};

/// Closed-form PPCA of S = sum_n w_n (x_n - m)(x_n - m)^T, m = sum_n w_n x_n, in O(n s + s^3)
/// for s samples of non-zero weight, without touching the d-dimensional data; with a factor
/// of r < s columns, in O(s r^2 + r^3) instead.
/// @param[in] G        n by n Gram matrix, G(i, j) = x_i . x_j (best of centred samples)
/// @param[in] weights  n non-negative weights summing to 1
/// @param[in] d        dimension of the samples, d > q
/// @param[in] q        latent dimension, q >= 1
/// @param[in] sigma2Floor  lower bound on sigma^2 (>= 0). With the floor active the result is
///                     still the constrained maximum-likelihood solution.
/// @param[in] factor   optional n by r matrix F with F F^T = G (the centred samples themselves
///                     when d < n): used when r is smaller than the support. Not owned.
/// Throws Error for q outside [1, d), DegenerateFit if no weight is positive or the
/// eigen-decomposition fails.
GramPpca fitPpcaGram(const Eigen::MatrixXd& G, const Eigen::VectorXd& weights, Eigen::Index d, int q, double sigma2Floor = 0.0,
    const Eigen::MatrixXd* factor = nullptr);

/// The model of a GramPpca in data space: mean = centre + Xc^T weights, W = Xc^T B.
/// @param[in] Xc      n by d samples after subtracting centre (the ones G was built from)
/// @param[in] centre  d vector that was subtracted from every sample
Ppca materialise(const Eigen::MatrixXd& Xc, const Eigen::VectorXd& centre, const GramPpca& fit);

/// PPCA through the eigenvectors of the d by d sample covariance. O(n d^2 + d^3): the
/// reference for small d.
/// @param[in] X  n by d samples, n >= 2; q < d
Ppca fitPpcaPrimal(const Eigen::MatrixXd& X, int q);

/// Dual PPCA (thesis 4.2.1.5): the same model through the n by n Gram matrix, O(n^2 d + n^3).
/// @param[in] X  n by d samples, n >= 2; q < d
Ppca fitPpcaDual(const Eigen::MatrixXd& X, int q);

/// fitPpcaDual when d > n, otherwise fitPpcaPrimal. Throws Error naming the row and column of
/// a NaN or infinity in X, or a q outside [1, d).
Ppca fitPpca(const Eigen::MatrixXd& X, int q);

/// The fewest principal directions of the samples that hold at least `fraction` of their
/// variance (the sum of the leading eigenvalues of the sample covariance over their total),
/// through the n by n Gram matrix when d > n: O(n^2 d + n^3), never a d by d matrix. 0 when
/// the samples do not vary.
/// @param[in] X         n by d samples, n >= 2
/// @param[in] fraction  in (0, 1]
/// Throws Error for a fraction outside (0, 1] or a NaN or infinity in X.
int dimensionHolding(const Eigen::MatrixXd& X, double fraction);

/// Posterior means of the latent variables, <x> = M^{-1} W^T (t - mu) with
/// M = sigma^2 I + W^T W (thesis eq. 4.19).
/// @param[in] T  m by d samples, one per row
/// @return m by q latent vectors, one per row
Eigen::MatrixXd latent(const Ppca& model, const Eigen::MatrixXd& T);

/// The sample of a latent vector by thesis eq. 4.20: mu + W (W^T W)^+ M x. For x = latent(t)
/// this is the orthogonal projection of t onto the affine subspace mu + span(W).
/// @param[in] Z  m by q latent vectors, one per row
/// @return m by d samples
Eigen::MatrixXd fromLatent(const Ppca& model, const Eigen::MatrixXd& Z);

/// Clean-up (thesis 4.2.4): fromLatent(latent(T)), the closest point of the model's subspace.
/// @param[in] T  m by d samples; returns m by d
Eigen::MatrixXd cleanUp(const Ppca& model, const Eigen::MatrixXd& T);

/// log N(t; mu, sigma^2 I + W W^T) for every row t of T, in nats, by the Woodbury identity
/// and the matrix determinant lemma: O(d q^2 + m d q), never a d by d matrix.
/// @param[in] T  m by d samples; returns m log-densities
Eigen::VectorXd logLikelihood(const Ppca& model, const Eigen::MatrixXd& T);

} // namespace facesketch::stats

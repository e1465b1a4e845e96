#pragma once
// The radial basis function (RBF) approximation of thesis 3.2.9: a smooth map of space that
// takes the template's feature points p_i onto a scan's q_i and carries every template vertex
// along, giving a face of the template's topology roughly shaped like the scan.
//
// The maths (thesis eqs. 3.1-3.3):
//   f(x) = sum_j c_j theta_j(x) + A x + t,
//   theta_j(x) = (|x - p_j|^2 + delta_j^2)^(-lambda), lambda = 1 (inverse multiquadric),
//   delta_j = min_{i != j} |p_i - p_j| (stiffness, after Eck 1991),
// with f(p_i) = q_i and the side conditions sum_j c_j = 0, sum_j c_j p_j^T = 0 that make the
// affine part the polynomial precision of the fit: if q_i = M p_i + b for all i, then c = 0 and
// f = M x + b exactly. The (n + 4) square system [K P; P^T 0] [c; (A t)^T] = [q; 0], K_ij =
// theta_j(p_i), P_i = (p_i^T, 1), is solved by a column-pivoting Householder QR (no normal
// equations; K is not symmetric since delta_j depends on j), whose rank decides degeneracy.

#include "core/mesh.h"

#include <Eigen/Core>

namespace facesketch::registration {

class RbfWarp {
public:
    /// Fits f(P.row(i)) = Q.row(i).
    /// @param[in] P  n by 3 source points (template), mm
    /// @param[in] Q  n by 3 target points (scan), mm
    /// Throws Error if the counts differ, n < 4, two source points coincide, or the points lie
    /// on one plane (the system is then rank deficient).
    RbfWarp(const Vertices& P, const Vertices& Q);

    /// f(x) for one point.
    Eigen::Vector3d apply(const Eigen::Vector3d& x) const;
    /// f applied to every row of V (#V by 3), #V by 3.
    Vertices apply(const Vertices& V) const;

    /// The affine part: f(x) = ... + linear() x + translation().
    const Eigen::Matrix3d& linear() const { return linear_; }
    const Eigen::Vector3d& translation() const { return translation_; }
    /// n by 3 RBF weights c_j.
    const Eigen::MatrixX3d& weights() const { return weights_; }
    /// delta_j of eq. 3.3, n values.
    const Eigen::VectorXd& stiffness() const { return stiffness_; }

private:
    Vertices centres_;
    Eigen::VectorXd stiffness_;
    Eigen::MatrixX3d weights_;
    Eigen::Matrix3d linear_;
    Eigen::Vector3d translation_;
};

} // namespace facesketch::registration

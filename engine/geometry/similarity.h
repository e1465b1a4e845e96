#pragma once
// The least-squares similarity (rotation, uniform scale, translation) between two sets of
// corresponding points, used to move the head's rigid parts with the skin around them
// (model/head_assembly.h).
//
// This work is based on:
//   Umeyama, "Least-squares estimation of transformation parameters between two point
//   patterns", IEEE TPAMI 13(4), 1991 (the closed-form similarity, with the reflection guard);
//   Kabsch, "A solution for the best rotation to relate two sets of vectors", Acta Cryst. A32,
//   1976 (the same without scale).
//
// The maths. For point pairs (x_i, y_i), i = 1..n, with centroids m_x, m_y, variance
// s_x^2 = 1/n sum |x_i - m_x|^2 and cross-covariance S = 1/n sum (y_i - m_y)(x_i - m_x)^T
// = U D V^T (SVD), the minimiser of sum |y_i - (c R x_i + t)|^2 over rotations R, scales c > 0
// and translations t is R = U E V^T with E = diag(1, 1, det(U V^T)), c = tr(D E) / s_x^2 and
// t = m_y - c R m_x. Check: points moved by any exact similarity come back exactly.

#include "core/mesh.h"

#include <Eigen/Core>

namespace facesketch {

/// y = scale * rotation * x + translation; rotation is proper (det +1), scale > 0.
struct Similarity {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    double scale = 1.0;
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();

    Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return scale * rotation * x + translation; }
    /// Every row of V (#V by 3) moved, #V by 3.
    Vertices apply(const Vertices& V) const;
};

/// The least-squares similarity (or, with allowScale false, rigid motion) taking `from` to `to`.
/// @param[in] from, to  n by 3 corresponding points, n >= 1
/// With fewer than 3 points, or points all on one line, the rotation is not determined and
/// the result is the translation of the centroids. Throws Error if the sizes differ or n = 0.
Similarity fitSimilarity(const Vertices& from, const Vertices& to, bool allowScale = true);

} // namespace facesketch

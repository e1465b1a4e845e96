#pragma once
// Rigid parts of the head (eyeballs, teeth, tongue) that follow the skin (issue 4): each part
// is stored on the mean head with a set of anchor skin vertices around it; after the skin is
// reconstructed, the least-squares similarity from the anchors' mean positions to their
// reconstructed positions moves the part, so an eyeball stays in its socket as the face
// changes shape.
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
#include <string>
#include <vector>

namespace facesketch::stats {

/// y = scale * rotation * x + translation.
struct Similarity {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    double scale = 1.0;
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();

    Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return scale * rotation * x + translation; }
    /// Every row of V moved.
    Vertices apply(const Vertices& V) const;
};

/// The least-squares similarity (or, with allowScale false, rigid motion) taking `from` to `to`.
/// @param[in] from, to  n by 3 corresponding points, n >= 1
/// With fewer than 3 points, or points all on one line, the rotation is not determined and
/// the result is the translation of the centroids. Throws Error if the sizes differ or n = 0.
Similarity fitSimilarity(const Vertices& from, const Vertices& to, bool allowScale = true);

/// A part of the head that moves as one body with the skin around it.
struct RigidPart {
    std::string name;
    /// Its vertices, indices into the whole head.
    std::vector<int> vertices;
    /// Their positions on the mean head, #vertices by 3 (mm).
    Vertices mean;
    /// Skin vertices (the face model's numbering) whose motion the part follows.
    std::vector<int> anchors;
    /// Similarity (true) or rigid motion (false).
    bool scale = true;
};

/// What the face model needs, beyond the skin, to rebuild the whole head.
struct HeadLayout {
    /// #V of the whole head; 0 if the model knows the skin only.
    int vertexCount = 0;
    /// Head index of the skin's vertex 0; skin vertex v is head vertex skinBegin + v.
    int skinBegin = 0;
    /// #F by 3 triangles of the whole head.
    Triangles topology;
    /// Every head vertex outside the skin belongs to exactly one part.
    std::vector<RigidPart> parts;
};

/// A part with anchors chosen on the mean head: the `anchorCount` skin vertices nearest the
/// centroid of the part's vertices (all skin vertices if there are fewer).
/// @param[in] meanSkin  #S by 3 skin vertices of the mean head (the model's numbering)
/// @param[in] meanHead  #V by 3 vertices of the mean head
RigidPart makeRigidPart(const std::string& name, const std::vector<int>& vertices, const Vertices& meanSkin, const Vertices& meanHead,
    int anchorCount, bool scale = true);

/// The whole head for a skin face: skin vertices from `skin` (3 #S values, laid out x0, y0,
/// z0, x1, ...), each part moved by the similarity fitted from its anchors' mean positions
/// (`meanSkin`, 3 #S values) to their positions in `skin`. Throws Error if the layout is
/// empty (vertexCount 0) or its sizes disagree with the skin.
Mesh assembleHead(const HeadLayout& layout, const Eigen::VectorXd& meanSkin, const Eigen::VectorXd& skin);

/// Throws Error naming `where` and the first inconsistency: a part vertex outside the head,
/// inside the skin or in two parts, a head vertex in no part, an anchor outside [0, skinVertices),
/// a mean of the wrong size, a triangle index outside the head.
void validateHeadLayout(const HeadLayout& layout, Eigen::Index skinVertices, const std::string& where);

} // namespace facesketch::stats

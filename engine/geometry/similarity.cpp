#include "geometry/similarity.h"

#include "core/error.h"

#include <Eigen/SVD>

namespace facesketch {

Vertices Similarity::apply(const Vertices& V) const
{
    Vertices out(V.rows(), 3);
    for (Eigen::Index i = 0; i < V.rows(); ++i)
        out.row(i) = apply(Eigen::Vector3d(V.row(i).transpose())).transpose();
    return out;
}

Similarity fitSimilarity(const Vertices& from, const Vertices& to, bool allowScale)
{
    if (from.rows() != to.rows() || from.rows() == 0)
        fail("fitSimilarity: ", from.rows(), " and ", to.rows(), " points, expected equal non-zero counts");
    const double n = static_cast<double>(from.rows());
    const Eigen::RowVector3d mx = from.colwise().mean(), my = to.colwise().mean();
    const Eigen::MatrixX3d X = from.rowwise() - mx, Y = to.rowwise() - my;
    const double varX = X.squaredNorm() / n;
    Similarity out;
    out.translation = (my - mx).transpose();
    if (from.rows() < 3 || !(varX > 0.0))
        return out;
    const Eigen::Matrix3d S = Y.transpose() * X / n;
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d D = svd.singularValues();
    // Collinear points leave the rotation about their line free.
    if (!(D(1) > 1e-12 * D(0)))
        return out;
    Eigen::Vector3d E(1.0, 1.0, 1.0);
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0)
        E(2) = -1.0; // the best orthogonal matrix would be a reflection
    out.rotation = svd.matrixU() * E.asDiagonal() * svd.matrixV().transpose();
    out.scale = allowScale ? D.dot(E) / varX : 1.0;
    out.translation = my.transpose() - out.scale * out.rotation * mx.transpose();
    return out;
}

} // namespace facesketch

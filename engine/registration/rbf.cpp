#include "registration/rbf.h"

#include "core/error.h"

#include <Eigen/QR>
#include <limits>

namespace facesketch::registration {

RbfWarp::RbfWarp(const Vertices& P, const Vertices& Q)
    : centres_(P)
{
    const Eigen::Index n = P.rows();
    if (Q.rows() != n)
        fail("RBF fit: ", n, " template points but ", Q.rows(), " scan points");
    if (n < 4)
        fail("RBF fit: ", n, " feature points, at least 4 not on one plane needed");
    if (!P.allFinite() || !Q.allFinite())
        fail("RBF fit: a feature point is not finite");
    stiffness_.resize(n);
    for (Eigen::Index j = 0; j < n; ++j) {
        double nearest = std::numeric_limits<double>::infinity();
        for (Eigen::Index i = 0; i < n; ++i)
            if (i != j)
                nearest = std::min(nearest, (P.row(i) - P.row(j)).norm());
        if (!(nearest > 0.0))
            fail("RBF fit: template feature points ", j, " and another coincide");
        stiffness_(j) = nearest;
    }
    Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n + 4, n + 4);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + 4, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j < n; ++j)
            system(i, j) = 1.0 / ((P.row(i) - P.row(j)).squaredNorm() + stiffness_(j) * stiffness_(j));
        for (int k = 0; k < 3; ++k) {
            system(i, n + k) = P(i, k);
            system(n + k, i) = P(i, k);
        }
        system(i, n + 3) = 1.0;
        system(n + 3, i) = 1.0;
        rhs.row(i) = Q.row(i);
    }
    // The kernel is ~1/mm^2 and the affine columns ~mm: scale the columns to one magnitude so the
    // QR's rank threshold compares like with like.
    Eigen::VectorXd scale = system.colwise().norm().transpose();
    for (Eigen::Index c = 0; c < scale.size(); ++c)
        scale(c) = scale(c) > 0.0 ? 1.0 / scale(c) : 1.0;
    const Eigen::MatrixXd scaled = system * scale.asDiagonal();
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
    qr.setThreshold(1e-10);
    if (qr.rank() < n + 4)
        fail("RBF fit: the ", n, " feature points lie on one plane (system rank ", qr.rank(), " of ", n + 4, ")");
    const Eigen::MatrixXd solution = scale.asDiagonal() * qr.solve(rhs);
    weights_ = solution.topRows(n);
    linear_ = solution.block(n, 0, 3, 3).transpose();
    translation_ = solution.row(n + 3).transpose();
}

Eigen::Vector3d RbfWarp::apply(const Eigen::Vector3d& x) const
{
    Eigen::Vector3d out = linear_ * x + translation_;
    for (Eigen::Index j = 0; j < centres_.rows(); ++j) {
        const double d2 = (x - centres_.row(j).transpose()).squaredNorm();
        out += weights_.row(j).transpose() / (d2 + stiffness_(j) * stiffness_(j));
    }
    return out;
}

Vertices RbfWarp::apply(const Vertices& V) const
{
    Vertices out(V.rows(), 3);
    for (Eigen::Index i = 0; i < V.rows(); ++i)
        out.row(i) = apply(Eigen::Vector3d(V.row(i).transpose())).transpose();
    return out;
}

} // namespace facesketch::registration

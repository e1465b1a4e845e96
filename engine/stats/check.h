#pragma once
// Input checks shared by the statistics entry points: a NaN that gets into an EM loop or a
// Cholesky factor comes out as a wrong face much later, so fit and infer calls reject it at
// the door and name the argument and the index.

#include "core/error.h"

#include <Eigen/Core>
#include <cmath>

namespace facesketch::stats {

/// Throws Error "<what>(i, j) = <value> is not finite" for the first NaN or infinity in A,
/// scanning in storage order.
template <typename Derived> void requireFinite(const Eigen::DenseBase<Derived>& A, const char* what)
{
    for (Eigen::Index j = 0; j < A.cols(); ++j)
        for (Eigen::Index i = 0; i < A.rows(); ++i)
            if (!std::isfinite(A(i, j)))
                fail(what, "(", i, ", ", j, ") = ", A(i, j), " is not finite");
}

} // namespace facesketch::stats

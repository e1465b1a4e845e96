#include "stats/random.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace facesketch::stats {

double Random::uniform()
{
    return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

std::int64_t Random::index(std::int64_t n)
{
    const auto range = static_cast<std::uint64_t>(n);
    // Reject the top partial block of 2^64 so every residue is equally likely.
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % range;
    std::uint64_t r = engine_();
    while (r >= limit)
        r = engine_();
    return static_cast<std::int64_t>(r % range);
}

double Random::normal()
{
    if (hasSpare_) {
        hasSpare_ = false;
        return spare_;
    }
    // 1 - uniform() lies in (0, 1], so the logarithm is finite.
    const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform()));
    const double angle = 2.0 * std::numbers::pi * uniform();
    spare_ = radius * std::sin(angle);
    hasSpare_ = true;
    return radius * std::cos(angle);
}

Eigen::MatrixXd Random::normalMatrix(Eigen::Index rows, Eigen::Index cols)
{
    Eigen::MatrixXd A(rows, cols);
    for (Eigen::Index j = 0; j < cols; ++j)
        for (Eigen::Index i = 0; i < rows; ++i)
            A(i, j) = normal();
    return A;
}

std::vector<int> Random::permutation(int n)
{
    std::vector<int> p(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
        p[static_cast<size_t>(i)] = i;
    for (int i = n - 1; i > 0; --i)
        std::swap(p[static_cast<size_t>(i)], p[static_cast<size_t>(index(i + 1))]);
    return p;
}

} // namespace facesketch::stats

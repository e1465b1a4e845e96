#include "core/random.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace facesketch {

std::uint64_t splitMix64(std::uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

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
    // u1 must lie in (0, 1] so that the logarithm is finite; see BoxMuller for the three ways.
    double u1 = 0, u2 = 0;
    switch (boxMuller_) {
    case BoxMuller::OneMinus:
        u1 = 1.0 - uniform();
        u2 = uniform();
        break;
    case BoxMuller::RedrawZero:
        while (u1 <= 0)
            u1 = uniform();
        u2 = uniform();
        break;
    case BoxMuller::PlusOne:
        u1 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
        u2 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
        break;
    }
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * std::numbers::pi * u2;
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

} // namespace facesketch

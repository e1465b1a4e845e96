#pragma once
// Deterministic random numbers for the statistics code, its tests and benchmarks.
//
// std::normal_distribution and std::uniform_int_distribution are implementation-defined, so
// the same seed gives different numbers under libstdc++ and libc++. Everything here is built
// only from the bits of std::mt19937_64, whose output sequence the standard fixes, so a seed
// names the same data set on every platform (up to the last bit of libm's log, sin and cos).

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

namespace facesketch::stats {

class Random {
public:
    explicit Random(std::uint64_t seed)
        : engine_(seed)
    {
    }

    /// Uniform in [0, 1) with 53 random bits.
    double uniform();

    /// Uniform integer in [0, n) without modulo bias. n must be positive.
    std::int64_t index(std::int64_t n);

    /// Standard normal N(0, 1) by the Box-Muller transform; values come in pairs, the second
    /// of each pair is kept for the next call.
    double normal();

    /// rows by cols matrix of independent standard normals, filled column by column.
    Eigen::MatrixXd normalMatrix(Eigen::Index rows, Eigen::Index cols);

    /// A uniformly random permutation of 0 .. n-1 (Fisher-Yates).
    std::vector<int> permutation(int n);

private:
    std::mt19937_64 engine_;
    double spare_ = 0.0;
    bool hasSpare_ = false;
};

} // namespace facesketch::stats

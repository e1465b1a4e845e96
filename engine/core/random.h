#pragma once
// The project's one random number generator: deterministic and portable.
//
// std::normal_distribution and std::uniform_int_distribution are implementation-defined, so
// the same seed gives different numbers under libstdc++ and libc++. Everything here is built
// only from the bits of std::mt19937_64, whose output sequence the standard fixes, so a seed
// names the same data on every platform (up to the last bit of libm's log, sin and cos).
// Statistics code, the synthetic face generator, the ICT import, tests and benchmarks all draw
// from this class; nothing else in the tree uses <random> distributions.
//
// Sources: Box and Muller, "A note on the generation of random normal deviates", 1958;
// SplitMix64: Steele, Lea and Flood, "Fast splittable pseudorandom number generators", 2014.

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

namespace facesketch {

/// SplitMix64's output function of x: x + 0x9E3779B97F4A7C15, then two xor-shift-multiply
/// rounds. Turns related seeds (seed, seed + 1, ...) into unrelated ones, so that each
/// identity of a dataset gets its own stream.
std::uint64_t splitMix64(std::uint64_t x);

/// How normal() turns the two 53-bit draws k1, k2 (the top bits of two engine outputs) of a
/// Box-Muller pair into u1 in (0, 1] (radius sqrt(-2 ln u1)) and u2 (angle 2 pi u2). All three
/// are exact standard normals; they differ only in which numbers a seed gives. They exist
/// because three generators were merged into this class with their streams kept, so that
/// every dataset written before stays byte-identical. New code uses the default.
enum class BoxMuller {
    /// u1 = 1 - k1 2^-53, u2 = k2 2^-53. The default (statistics, tests, benchmarks).
    OneMinus,
    /// u1 = k1 2^-53 with k1 = 0 drawn again, u2 = k2 2^-53. The synthetic face generator
    /// (dataset/synth/face_params.h): its faces are byte-identical to the earlier releases'.
    RedrawZero,
    /// u1 = (k1 + 1) 2^-53, u2 = (k2 + 1) 2^-53. The ICT identity coefficients
    /// (dataset/import_ict.h): its faces are byte-identical to the earlier releases'.
    PlusOne,
};

class Random {
public:
    explicit Random(std::uint64_t seed, BoxMuller boxMuller = BoxMuller::OneMinus)
        : engine_(seed)
        , boxMuller_(boxMuller)
    {
    }

    /// Uniform in [0, 1): the top 53 bits of one engine output times 2^-53.
    double uniform();

    /// Uniform in [lo, hi): lo + (hi - lo) uniform().
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

    /// Uniform integer in [0, n) without modulo bias (the top partial block of 2^64 is drawn
    /// again, so the result is engine() % n except with probability below n / 2^64). n > 0.
    std::int64_t index(std::int64_t n);

    /// Standard normal N(0, 1) by the Box-Muller transform (the BoxMuller chosen at
    /// construction); values come in pairs, cos then sin, and the second of each pair is kept
    /// for the next call.
    double normal();

    /// rows by cols matrix of independent standard normals, filled column by column.
    Eigen::MatrixXd normalMatrix(Eigen::Index rows, Eigen::Index cols);

    /// A uniformly random permutation of 0 .. n-1 (Fisher-Yates from the top: position i
    /// swaps with index(i + 1), for i = n-1 down to 1).
    std::vector<int> permutation(int n);

private:
    std::mt19937_64 engine_;
    BoxMuller boxMuller_;
    double spare_ = 0.0;
    bool hasSpare_ = false;
};

} // namespace facesketch

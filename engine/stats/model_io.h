#pragma once
// The binary container and payload coding shared by the model files (the face model,
// stats/model_file.h, and the pose model, pose/pose_file.h).
//
// Container (little-endian): 8 magic bytes, a u32 format version, a u64 payload length, the
// payload, then the u64 FNV-1a hash of the payload (core/hash.h), written atomically
// (core/atomic_file.h). Payload: scalars in host (little-endian) order; a matrix is u64 rows,
// u64 cols, then its values column-major; a string is a u64 length and its bytes; a PPCA is
// mean, W, sigma^2; a mixture is its priors, a u64 component count and the components.

#include "stats/mppca.h"
#include "stats/ppca.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace facesketch::stats {

/// Builds a payload in memory.
class PayloadWriter {
public:
    template <typename T> void scalar(T value) { bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T)); }
    template <typename Derived> void matrix(const Eigen::DenseBase<Derived>& A)
    {
        scalar<std::uint64_t>(static_cast<std::uint64_t>(A.rows()));
        scalar<std::uint64_t>(static_cast<std::uint64_t>(A.cols()));
        using Scalar = typename Derived::Scalar;
        const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> plain = A; // column-major
        bytes_.append(reinterpret_cast<const char*>(plain.data()), sizeof(Scalar) * static_cast<size_t>(plain.size()));
    }
    void ppca(const Ppca& p);
    void mixture(const Mppca& m);
    void text(const std::string& t);
    void indices(const std::vector<int>& list);
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

/// Reads a payload; every read names what it reads, and a read past the end throws Error
/// "<path>: truncated at byte N reading <what>".
class PayloadReader {
public:
    /// Reads bytes[begin, end). Keeps references to bytes and path: keep them alive.
    PayloadReader(const std::string& bytes, size_t begin, size_t end, const std::filesystem::path& path);

    template <typename T> T scalar(const char* what)
    {
        need(sizeof(T), what);
        T value;
        std::memcpy(&value, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return value;
    }
    template <typename Scalar> Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> matrix(const char* what)
    {
        const auto rows = scalar<std::uint64_t>(what);
        const auto cols = scalar<std::uint64_t>(what);
        checkSize(rows, cols, sizeof(Scalar), what);
        Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> A(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
        const size_t size = sizeof(Scalar) * static_cast<size_t>(rows * cols);
        if (size > 0)
            std::memcpy(A.data(), bytes_.data() + at_, size);
        at_ += size;
        return A;
    }
    /// A matrix that must have one column.
    Eigen::VectorXd vector(const char* what);
    /// A PPCA whose W has as many rows as its mean and whose sigma^2 is positive.
    Ppca ppca(const char* what);
    /// A mixture whose component count equals its prior count.
    Mppca mixture(const char* what);
    std::string text(const char* what);
    std::vector<int> indices(const char* what);
    bool done() const { return at_ == end_; }
    size_t at() const { return at_; }
    const std::filesystem::path& path() const { return path_; }

private:
    void need(size_t size, const char* what) const;
    void checkSize(std::uint64_t rows, std::uint64_t cols, size_t scalarSize, const char* what) const;
    const std::string& bytes_;
    size_t at_;
    size_t end_;
    std::filesystem::path path_; // a copy: readers are made with temporaries too
};

/// Writes magic, version, length, payload and hash to path atomically. Throws Error naming path.
void writeModelContainer(
    const std::filesystem::path& path, const std::array<char, 8>& magic, std::uint32_t version, const std::string& payload);

/// Reads a file written by writeModelContainer and returns its payload. Throws Error naming the
/// path: "cannot open", "not a FaceSketch <kind> (no <magic> header)", "<kind> format version V,
/// this program reads version W; <remedy>", a length that disagrees with the file size
/// ("truncated or has trailing data"), or "checksum mismatch".
std::string readModelContainer(const std::filesystem::path& path, const std::array<char, 8>& magic, std::uint32_t version,
    const std::string& kind, const std::string& remedy);

} // namespace facesketch::stats

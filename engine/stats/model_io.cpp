#include "stats/model_io.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/limits.h"

#include <bit>
#include <fstream>
#include <iterator>

namespace facesketch::stats {

static_assert(std::endian::native == std::endian::little, "the model files are written in host order");

void PayloadWriter::ppca(const Ppca& p)
{
    matrix(p.mean);
    matrix(p.W);
    scalar(p.sigma2);
}

void PayloadWriter::mixture(const Mppca& m)
{
    matrix(m.priors);
    scalar<std::uint64_t>(m.components.size());
    for (const Ppca& p : m.components)
        ppca(p);
}

void PayloadWriter::text(const std::string& t)
{
    scalar<std::uint64_t>(t.size());
    bytes_.append(t);
}

void PayloadWriter::indices(const std::vector<int>& list)
{
    matrix(Eigen::Map<const Eigen::VectorXi>(list.data(), static_cast<Eigen::Index>(list.size())));
}

PayloadReader::PayloadReader(const std::string& bytes, size_t begin, size_t end, const std::filesystem::path& path)
    : bytes_(bytes)
    , at_(begin)
    , end_(end)
    , path_(path)
{
}

void PayloadReader::need(size_t size, const char* what) const
{
    if (end_ - at_ < size)
        fail(path_.string(), ": truncated at byte ", at_, " reading ", what);
}

void PayloadReader::checkSize(std::uint64_t rows, std::uint64_t cols, size_t scalarSize, const char* what) const
{
    // Checked by division so a corrupt size cannot overflow the product; each side on its own
    // too, as a matrix with no columns may claim any number of rows (found by fuzzing).
    constexpr std::uint64_t kMaxSide = std::uint64_t(1) << 32;
    if (rows > kMaxSide || cols > kMaxSide || (cols != 0 && rows > (end_ - at_) / scalarSize / cols))
        fail(path_.string(), ": ", what, " claims ", rows, " by ", cols, " values at byte ", at_, ", more than the file holds");
}

Eigen::VectorXd PayloadReader::vector(const char* what)
{
    const Eigen::MatrixXd A = matrix<double>(what);
    if (A.cols() != 1)
        fail(path_.string(), ": ", what, " is ", A.rows(), " by ", A.cols(), ", expected a column");
    return A.col(0);
}

Ppca PayloadReader::ppca(const char* what)
{
    Ppca p;
    p.mean = vector(what);
    p.W = matrix<double>(what);
    p.sigma2 = scalar<double>(what);
    // q <= d keeps everything derived from W (the q by q W^T W) within the file's size.
    if (p.W.rows() != p.mean.size() || p.W.cols() > p.W.rows() || !(p.sigma2 > 0.0))
        fail(path_.string(), ": ", what, " is inconsistent (", p.mean.size(), " means, W ", p.W.rows(), " by ", p.W.cols(), ", sigma^2 ",
            p.sigma2, ")");
    return p;
}

Mppca PayloadReader::mixture(const char* what)
{
    Mppca m;
    m.priors = vector(what);
    const auto K = scalar<std::uint64_t>(what);
    if (K != static_cast<std::uint64_t>(m.priors.size()))
        fail(path_.string(), ": ", what, " has ", K, " components and ", m.priors.size(), " priors");
    for (std::uint64_t k = 0; k < K; ++k)
        m.components.push_back(ppca(what));
    return m;
}

std::string PayloadReader::text(const char* what)
{
    const auto size = scalar<std::uint64_t>(what);
    need(size, what);
    std::string t(bytes_.data() + at_, static_cast<size_t>(size));
    at_ += static_cast<size_t>(size);
    return t;
}

std::vector<int> PayloadReader::indices(const char* what)
{
    const Eigen::MatrixXi list = matrix<int>(what);
    return { list.data(), list.data() + list.size() };
}

void writeModelContainer(
    const std::filesystem::path& path, const std::array<char, 8>& magic, std::uint32_t version, const std::string& payload)
{
    writeFileAtomically(path, [&](std::ostream& out) {
        out.write(magic.data(), static_cast<std::streamsize>(magic.size()));
        const std::uint64_t length = payload.size();
        const std::uint64_t hash = fnv1a(payload.data(), payload.size());
        out.write(reinterpret_cast<const char*>(&version), sizeof(version));
        out.write(reinterpret_cast<const char*>(&length), sizeof(length));
        out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
        out.write(reinterpret_cast<const char*>(&hash), sizeof(hash));
    });
}

std::string readModelContainer(const std::filesystem::path& path, const std::array<char, 8>& magic, std::uint32_t version,
    const std::string& kind, const std::string& remedy)
{
    if (!std::filesystem::is_regular_file(path))
        fail(path.string(), ": cannot open the ", kind, " file");
    const std::string bytes = limits::readFileLimited(path, limits::kMaxModelFileBytes, ("a " + kind + " file").c_str());
    const size_t header = magic.size() + sizeof(std::uint32_t) + sizeof(std::uint64_t);
    if (bytes.size() < magic.size() || std::memcmp(bytes.data(), magic.data(), magic.size()) != 0)
        fail(path.string(), ": not a FaceSketch ", kind, " (no ", std::string(magic.data()), " header)");
    PayloadReader head(bytes, magic.size(), bytes.size(), path);
    const auto found = head.scalar<std::uint32_t>("the version");
    if (found != version)
        fail(path.string(), ": ", kind, " format version ", found, ", this program reads version ", version, "; ", remedy);
    const auto length = head.scalar<std::uint64_t>("the payload length");
    if (length > bytes.size() - header || bytes.size() - header - length != sizeof(std::uint64_t))
        fail(path.string(), ": ", bytes.size(), " bytes, but the header announces ", length,
            " bytes of payload; the file is truncated or has trailing data");
    std::string payload = bytes.substr(header, static_cast<size_t>(length));
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + header + length, sizeof(stored));
    if (fnv1a(payload.data(), payload.size()) != stored)
        fail(path.string(), ": checksum mismatch, the file is corrupt");
    return payload;
}

} // namespace facesketch::stats

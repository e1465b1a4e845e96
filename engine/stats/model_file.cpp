#include "stats/model_file.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/limits.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

namespace facesketch::stats {

static_assert(std::endian::native == std::endian::little, "the model file is written in host order");

namespace {

constexpr char kMagic[8] = { 'F', 'S', 'K', 'F', 'A', 'C', 'E', '\0' };

std::uint64_t fnv1a(const std::string& bytes)
{
    return facesketch::fnv1a(bytes.data(), bytes.size());
}

class Writer {
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
    void ppca(const Ppca& p)
    {
        matrix(p.mean);
        matrix(p.W);
        scalar(p.sigma2);
    }
    void mixture(const Mppca& m)
    {
        matrix(m.priors);
        scalar<std::uint64_t>(m.components.size());
        for (const Ppca& p : m.components)
            ppca(p);
    }
    void text(const std::string& t)
    {
        scalar<std::uint64_t>(t.size());
        bytes_.append(t);
    }
    void indices(const std::vector<int>& list)
    {
        matrix(Eigen::Map<const Eigen::VectorXi>(list.data(), static_cast<Eigen::Index>(list.size())));
    }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

class Reader {
public:
    Reader(const std::string& bytes, size_t begin, size_t end, const std::filesystem::path& path)
        : bytes_(bytes)
        , at_(begin)
        , end_(end)
        , path_(path)
    {
    }
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
        // Checked by division so a corrupt size cannot overflow the product; each side on its
        // own too, as a matrix with no columns may claim any number of rows.
        constexpr std::uint64_t kMaxSide = std::uint64_t(1) << 32;
        if (rows > kMaxSide || cols > kMaxSide || (cols != 0 && rows > (end_ - at_) / sizeof(Scalar) / cols))
            fail(path_.string(), ": ", what, " claims ", rows, " by ", cols, " values at byte ", at_, ", more than the file holds");
        Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> A(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
        const size_t size = sizeof(Scalar) * static_cast<size_t>(rows * cols);
        if (size > 0)
            std::memcpy(A.data(), bytes_.data() + at_, size);
        at_ += size;
        return A;
    }
    Eigen::VectorXd vector(const char* what)
    {
        const Eigen::MatrixXd A = matrix<double>(what);
        if (A.cols() != 1)
            fail(path_.string(), ": ", what, " is ", A.rows(), " by ", A.cols(), ", expected a column");
        return A.col(0);
    }
    Ppca ppca(const char* what)
    {
        Ppca p;
        p.mean = vector(what);
        p.W = matrix<double>(what);
        p.sigma2 = scalar<double>(what);
        // q <= d keeps everything derived from W (the q by q W^T W) within the file's size.
        if (p.W.rows() != p.mean.size() || p.W.cols() > p.W.rows() || !(p.sigma2 > 0.0))
            fail(path_.string(), ": ", what, " is inconsistent (", p.mean.size(), " means, W ", p.W.rows(), " by ", p.W.cols(),
                ", sigma^2 ", p.sigma2, ")");
        return p;
    }
    Mppca mixture(const char* what)
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
    std::string text(const char* what)
    {
        const auto size = scalar<std::uint64_t>(what);
        need(size, what);
        std::string t(bytes_.data() + at_, static_cast<size_t>(size));
        at_ += static_cast<size_t>(size);
        return t;
    }
    std::vector<int> indices(const char* what)
    {
        const Eigen::MatrixXi list = matrix<int>(what);
        return { list.data(), list.data() + list.size() };
    }
    bool done() const { return at_ == end_; }
    size_t at() const { return at_; }

private:
    void need(size_t size, const char* what) const
    {
        if (end_ - at_ < size)
            fail(path_.string(), ": truncated at byte ", at_, " reading ", what);
    }
    const std::string& bytes_;
    size_t at_;
    size_t end_;
    const std::filesystem::path& path_;
};

} // namespace

void saveFaceModel(const FaceModel& model, const std::filesystem::path& path)
{
    Writer w;
    w.matrix(model.triangles);
    w.matrix(model.meanFace);
    w.matrix(model.segmentation.core);
    w.scalar<std::uint64_t>(model.segmentation.vertices.size());
    for (size_t s = 0; s < model.segmentation.vertices.size(); ++s) {
        const auto& members = model.segmentation.vertices[s];
        w.matrix(Eigen::Map<const Eigen::VectorXi>(members.data(), static_cast<Eigen::Index>(members.size())));
        w.matrix(model.segmentation.weights[s]);
    }
    w.scalar<std::uint64_t>(model.segments.size());
    for (const SegmentModel& sm : model.segments) {
        w.mixture(sm.mixture);
        w.ppca(sm.cleanUp);
        w.scalar(sm.logLikelihood);
    }
    w.mixture(model.correlation);
    const HeadLayout& head = model.head;
    w.scalar<std::int64_t>(head.vertexCount);
    w.scalar<std::int64_t>(head.skinBegin);
    w.matrix(head.topology);
    w.scalar<std::uint64_t>(head.parts.size());
    for (const RigidPart& part : head.parts) {
        w.text(part.name);
        w.indices(part.vertices);
        w.matrix(part.mean);
        w.indices(part.anchors);
        w.scalar<std::uint8_t>(part.scale ? 1 : 0);
    }

    writeFileAtomically(path, [&](std::ostream& out) {
        out.write(kMagic, sizeof(kMagic));
        const std::uint32_t version = kFaceModelVersion;
        const std::uint64_t length = w.bytes().size();
        const std::uint64_t hash = fnv1a(w.bytes());
        out.write(reinterpret_cast<const char*>(&version), sizeof(version));
        out.write(reinterpret_cast<const char*>(&length), sizeof(length));
        out.write(w.bytes().data(), static_cast<std::streamsize>(w.bytes().size()));
        out.write(reinterpret_cast<const char*>(&hash), sizeof(hash));
    });
}

FaceModel loadFaceModel(const std::filesystem::path& path)
{
    if (!std::filesystem::is_regular_file(path))
        fail(path.string(), ": cannot open the model file");
    const std::string bytes = limits::readFileLimited(path, limits::kMaxModelFileBytes, "a face model file");
    const size_t header = sizeof(kMagic) + sizeof(std::uint32_t) + sizeof(std::uint64_t);
    if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
        fail(path.string(), ": not a FaceSketch face model (no FSKFACE header)");
    Reader head(bytes, sizeof(kMagic), bytes.size(), path);
    const auto version = head.scalar<std::uint32_t>("the version");
    if (version != kFaceModelVersion)
        fail(path.string(), ": model format version ", version, ", this program reads version ", kFaceModelVersion, "; retrain the model");
    const auto length = head.scalar<std::uint64_t>("the payload length");
    if (length > bytes.size() - header || bytes.size() - header - length != sizeof(std::uint64_t))
        fail(path.string(), ": ", bytes.size(), " bytes, but the header announces ", length,
            " bytes of payload; the file is truncated or has trailing data");
    const std::string payload = bytes.substr(header, static_cast<size_t>(length));
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + header + length, sizeof(stored));
    if (fnv1a(payload) != stored)
        fail(path.string(), ": checksum mismatch, the file is corrupt");

    Reader r(payload, 0, payload.size(), path);
    FaceModel model;
    const Eigen::MatrixXi triangles = r.matrix<std::int32_t>("the triangles");
    if (triangles.cols() != 3)
        fail(path.string(), ": the triangles have ", triangles.cols(), " columns, expected 3");
    model.triangles = triangles;
    model.meanFace = r.vector("the mean face");
    model.segmentation.core = r.matrix<int>("the segment labels").reshaped();
    const auto groups = r.scalar<std::uint64_t>("the segment count");
    for (std::uint64_t s = 0; s < groups; ++s) {
        const Eigen::MatrixXi members = r.matrix<int>("a segment's vertices");
        model.segmentation.vertices.emplace_back(members.data(), members.data() + members.size());
        model.segmentation.weights.push_back(r.vector("a segment's blend weights"));
    }
    const auto segments = r.scalar<std::uint64_t>("the segment model count");
    if (segments != groups)
        fail(path.string(), ": ", groups, " segments but ", segments, " segment models");
    for (std::uint64_t s = 0; s < segments; ++s) {
        SegmentModel sm;
        sm.mixture = r.mixture("a segment mixture");
        sm.cleanUp = r.ppca("a segment clean-up model");
        sm.logLikelihood = r.scalar<double>("a segment log-likelihood");
        model.segments.push_back(std::move(sm));
    }
    model.correlation = r.mixture("the correlation mixture");
    HeadLayout& layout = model.head;
    const auto headVertices = r.scalar<std::int64_t>("the head vertex count");
    const auto skinBegin = r.scalar<std::int64_t>("the skin offset");
    if (headVertices < 0 || headVertices > limits::kMaxMeshVertices || skinBegin < 0 || skinBegin > headVertices)
        fail(path.string(), ": head of ", headVertices, " vertices with the skin from ", skinBegin);
    layout.vertexCount = static_cast<int>(headVertices);
    layout.skinBegin = static_cast<int>(skinBegin);
    const Eigen::MatrixXi headTriangles = r.matrix<std::int32_t>("the head triangles");
    if (headTriangles.size() == 0)
        layout.topology.resize(0, 3);
    else if (headTriangles.cols() != 3)
        fail(path.string(), ": the head triangles have ", headTriangles.cols(), " columns, expected 3");
    else
        layout.topology = headTriangles;
    const auto parts = r.scalar<std::uint64_t>("the rigid part count");
    for (std::uint64_t p = 0; p < parts; ++p) {
        RigidPart part;
        part.name = r.text("a rigid part name");
        part.vertices = r.indices("a rigid part's vertices");
        const Eigen::MatrixXd mean = r.matrix<double>("a rigid part's mean positions");
        if (mean.cols() != 3)
            fail(path.string(), ": rigid part '", part.name, "' has mean positions with ", mean.cols(), " columns");
        part.mean = mean;
        part.anchors = r.indices("a rigid part's anchors");
        part.scale = r.scalar<std::uint8_t>("a rigid part's scale flag") != 0;
        layout.parts.push_back(std::move(part));
    }
    if (!r.done())
        fail(path.string(), ": ", payload.size() - r.at(), " unread bytes at the end of the payload");

    // The checksum guards against corruption, not against a writer bug: check that the parts
    // fit together before anything indexes with them.
    const Eigen::Index vertices = model.vertexCount();
    auto inconsistent = [&](const auto&... what) { fail(path.string(), ": inconsistent model: ", what...); };
    if (model.meanFace.size() % 3 != 0 || model.segmentation.core.size() != vertices)
        inconsistent("mean face of ", model.meanFace.size(), " values, ", model.segmentation.core.size(), " segment labels");
    if (model.triangles.size() > 0 && (model.triangles.minCoeff() < 0 || model.triangles.maxCoeff() >= vertices))
        inconsistent("a triangle index outside [0, ", vertices, ")");
    if (model.segmentation.core.size() > 0
        && (model.segmentation.core.minCoeff() < 0 || static_cast<std::uint64_t>(model.segmentation.core.maxCoeff()) >= groups))
        inconsistent("a segment label outside [0, ", groups, ")");
    Eigen::Index latents = 0;
    for (std::uint64_t s = 0; s < segments; ++s) {
        const auto& members = model.segmentation.vertices[s];
        const SegmentModel& sm = model.segments[s];
        const auto d = 3 * static_cast<Eigen::Index>(members.size());
        if (members.empty())
            inconsistent("segment ", s, " has no vertices");
        for (int v : members)
            if (v < 0 || v >= vertices)
                inconsistent("segment ", s, " holds vertex ", v, " outside [0, ", vertices, ")");
        if (model.segmentation.weights[s].size() != static_cast<Eigen::Index>(members.size()) || sm.cleanUp.dim() != d)
            inconsistent("segment ", s, " has ", members.size(), " vertices but other sizes disagree");
        for (const Ppca& p : sm.mixture.components)
            if (p.dim() != d)
                inconsistent("segment ", s, " has a mixture component of dimension ", p.dim(), ", expected ", d);
        latents += sm.cleanUp.latentDim();
    }
    for (const Ppca& p : model.correlation.components)
        if (p.dim() != latents)
            inconsistent("the correlation mixture has dimension ", p.dim(), ", expected ", latents);
    // Every head vertex is skin or in one rigid part: check the count before validateHeadLayout
    // allocates per head vertex.
    Eigen::Index partVertices = 0;
    for (const RigidPart& part : layout.parts)
        partVertices += static_cast<Eigen::Index>(part.vertices.size());
    if (layout.vertexCount > vertices + partVertices)
        inconsistent("a head of ", layout.vertexCount, " vertices from ", vertices, " skin and ", partVertices, " rigid-part vertices");
    if (layout.vertexCount > 0)
        validateHeadLayout(layout, vertices, path.string() + ": inconsistent model");
    else if (!layout.parts.empty() || layout.topology.size() > 0)
        inconsistent("rigid parts or head triangles without a head");
    deriveFaceModel(model);
    return model;
}

} // namespace facesketch::stats

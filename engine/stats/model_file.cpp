#include "stats/model_file.h"

#include "core/error.h"
#include "core/limits.h"
#include "stats/model_io.h"

#include <array>
#include <limits>
#include <string>

namespace facesketch::stats {

namespace {

constexpr std::array<char, 8> kMagic = { 'F', 'S', 'K', 'F', 'A', 'C', 'E', '\0' };

} // namespace

void saveFaceModel(const FaceModel& model, const std::filesystem::path& path)
{
    PayloadWriter w;
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

    writeModelContainer(path, kMagic, kFaceModelVersion, w.bytes());
}

FaceModel loadFaceModel(const std::filesystem::path& path)
{
    const std::string payload = readModelContainer(path, kMagic, kFaceModelVersion, "face model", "retrain the model");
    PayloadReader r(payload, 0, payload.size(), path);
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

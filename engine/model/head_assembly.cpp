#include "model/head_assembly.h"

#include "core/error.h"
#include "geometry/similarity.h"

#include <algorithm>
#include <numeric>

namespace facesketch::model {

using stats::HeadLayout;
using stats::RigidPart;

RigidPart makeRigidPart(const std::string& name, const std::vector<int>& vertices, const Vertices& meanSkin, const Vertices& meanHead,
    int anchorCount, bool scale)
{
    if (vertices.empty())
        fail("rigid part '", name, "' has no vertices");
    if (meanSkin.rows() == 0 || anchorCount < 1)
        fail("rigid part '", name, "': ", meanSkin.rows(), " skin vertices, ", anchorCount, " anchors asked");
    RigidPart part;
    part.name = name;
    part.vertices = vertices;
    part.scale = scale;
    part.mean.resize(static_cast<Eigen::Index>(vertices.size()), 3);
    for (size_t i = 0; i < vertices.size(); ++i) {
        if (vertices[i] < 0 || vertices[i] >= meanHead.rows())
            fail("rigid part '", name, "': vertex ", vertices[i], " outside [0, ", meanHead.rows(), ")");
        part.mean.row(static_cast<Eigen::Index>(i)) = meanHead.row(vertices[i]);
    }
    const Eigen::RowVector3d centre = part.mean.colwise().mean();
    std::vector<int> order(static_cast<size_t>(meanSkin.rows()));
    std::iota(order.begin(), order.end(), 0);
    const auto count = std::min<size_t>(static_cast<size_t>(anchorCount), order.size());
    auto distance = [&](int v) { return (meanSkin.row(v) - centre).squaredNorm(); };
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(),
        [&](int a, int b) { return distance(a) < distance(b) || (distance(a) == distance(b) && a < b); });
    part.anchors.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count));
    std::sort(part.anchors.begin(), part.anchors.end());
    return part;
}

Mesh assembleHead(const HeadLayout& layout, const Eigen::VectorXd& meanSkin, const Eigen::VectorXd& skin)
{
    if (layout.vertexCount == 0)
        fail("assembleHead: the model holds the skin only (trained without a head layout)");
    if (skin.size() != meanSkin.size() || skin.size() % 3 != 0)
        fail("assembleHead: skin of ", skin.size(), " values, mean skin of ", meanSkin.size());
    const Eigen::Index S = skin.size() / 3;
    if (layout.skinBegin + S > layout.vertexCount)
        fail("assembleHead: ", S, " skin vertices from ", layout.skinBegin, " do not fit a head of ", layout.vertexCount);
    Mesh head;
    head.F = layout.topology;
    head.V.setZero(layout.vertexCount, 3);
    for (Eigen::Index v = 0; v < S; ++v)
        head.V.row(layout.skinBegin + v) = skin.segment<3>(3 * v).transpose();
    for (const RigidPart& part : layout.parts) {
        Vertices from(static_cast<Eigen::Index>(part.anchors.size()), 3), to(from.rows(), 3);
        for (size_t i = 0; i < part.anchors.size(); ++i) {
            if (part.anchors[i] < 0 || part.anchors[i] >= S)
                fail("assembleHead: part '", part.name, "' anchor ", part.anchors[i], " outside [0, ", S, ")");
            from.row(static_cast<Eigen::Index>(i)) = meanSkin.segment<3>(3 * part.anchors[i]).transpose();
            to.row(static_cast<Eigen::Index>(i)) = skin.segment<3>(3 * part.anchors[i]).transpose();
        }
        const Vertices moved = fitSimilarity(from, to, part.scale).apply(part.mean);
        for (size_t i = 0; i < part.vertices.size(); ++i)
            head.V.row(part.vertices[i]) = moved.row(static_cast<Eigen::Index>(i));
    }
    return head;
}

Mesh reconstructHead(const stats::FaceModel& model, const stats::Observations& observations, const stats::ReconstructOptions& options)
{
    return assembleHead(model.head, model.meanFace, stats::reconstruct(model, observations, options).face);
}

} // namespace facesketch::model

#include "stats/rigid.h"

#include "core/error.h"

#include <Eigen/SVD>
#include <algorithm>
#include <numeric>

namespace facesketch::stats {

Vertices Similarity::apply(const Vertices& V) const
{
    Vertices out(V.rows(), 3);
    for (Eigen::Index i = 0; i < V.rows(); ++i)
        out.row(i) = apply(Eigen::Vector3d(V.row(i).transpose())).transpose();
    return out;
}

Similarity fitSimilarity(const Vertices& from, const Vertices& to, bool allowScale)
{
    if (from.rows() != to.rows() || from.rows() == 0)
        fail("fitSimilarity: ", from.rows(), " and ", to.rows(), " points, expected equal non-zero counts");
    const double n = static_cast<double>(from.rows());
    const Eigen::RowVector3d mx = from.colwise().mean(), my = to.colwise().mean();
    const Eigen::MatrixX3d X = from.rowwise() - mx, Y = to.rowwise() - my;
    const double varX = X.squaredNorm() / n;
    Similarity out;
    out.translation = (my - mx).transpose();
    if (from.rows() < 3 || !(varX > 0.0))
        return out;
    const Eigen::Matrix3d S = Y.transpose() * X / n;
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d D = svd.singularValues();
    // Collinear points leave the rotation about their line free.
    if (!(D(1) > 1e-12 * D(0)))
        return out;
    Eigen::Vector3d E(1.0, 1.0, 1.0);
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0)
        E(2) = -1.0; // the best orthogonal matrix would be a reflection
    out.rotation = svd.matrixU() * E.asDiagonal() * svd.matrixV().transpose();
    out.scale = allowScale ? D.dot(E) / varX : 1.0;
    out.translation = my.transpose() - out.scale * out.rotation * mx.transpose();
    return out;
}

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

void validateHeadLayout(const HeadLayout& layout, Eigen::Index skinVertices, const std::string& where)
{
    const int V = layout.vertexCount;
    if (V <= 0 || layout.skinBegin < 0 || layout.skinBegin + skinVertices > V)
        fail(where, ": head of ", V, " vertices cannot hold ", skinVertices, " skin vertices from ", layout.skinBegin);
    std::vector<int> owner(static_cast<size_t>(V), -1);
    for (Eigen::Index v = 0; v < skinVertices; ++v)
        owner[static_cast<size_t>(layout.skinBegin + v)] = 0;
    for (size_t p = 0; p < layout.parts.size(); ++p) {
        const RigidPart& part = layout.parts[p];
        if (part.mean.rows() != static_cast<Eigen::Index>(part.vertices.size()) || part.anchors.empty())
            fail(where, ": rigid part '", part.name, "' has ", part.vertices.size(), " vertices, ", part.mean.rows(),
                " mean positions and ", part.anchors.size(), " anchors");
        for (int v : part.vertices) {
            if (v < 0 || v >= V)
                fail(where, ": rigid part '", part.name, "' holds vertex ", v, " outside [0, ", V, ")");
            if (owner[static_cast<size_t>(v)] != -1)
                fail(where, ": rigid part '", part.name, "' holds vertex ", v, ", already in the skin or another part");
            owner[static_cast<size_t>(v)] = 1;
        }
        for (int a : part.anchors)
            if (a < 0 || a >= skinVertices)
                fail(where, ": rigid part '", part.name, "' has anchor ", a, " outside the skin [0, ", skinVertices, ")");
    }
    const auto missing = std::find(owner.begin(), owner.end(), -1);
    if (missing != owner.end())
        fail(where, ": head vertex ", missing - owner.begin(), " is neither skin nor in a rigid part");
    if (layout.topology.size() > 0 && (layout.topology.minCoeff() < 0 || layout.topology.maxCoeff() >= V))
        fail(where, ": a head triangle index outside [0, ", V, ")");
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

} // namespace facesketch::stats

#include "pose/mapping.h"

#include "core/error.h"
#include "registration/rbf.h"
#include "stats/check.h"
#include "stats/conditional.h"

#include <Eigen/Dense>
#include <algorithm>

namespace facesketch::pose {

namespace {

int clampLatent(int wanted, Eigen::Index n, Eigen::Index d)
{
    return static_cast<int>(std::clamp<Eigen::Index>(wanted, 1, std::min(n - 1, d - 1)));
}

} // namespace

PoseMapping fitMapping(const Eigen::MatrixXd& fp, const Eigen::MatrixXd& mesh, const MappingOptions& options)
{
    if (fp.rows() != mesh.rows())
        fail("fitMapping: ", fp.rows(), " FP poses but ", mesh.rows(), " mesh poses");
    if (fp.rows() < 3)
        fail("fitMapping: ", fp.rows(), " poses, the mapping needs at least 3");
    stats::requireFinite(fp, "fitMapping: FP poses");
    stats::requireFinite(mesh, "fitMapping: mesh poses");
    const Eigen::Index n = fp.rows();

    PoseMapping m;
    m.fp = stats::fitPpca(fp, clampLatent(options.fpLatentDim, n, fp.cols()));
    m.mesh = stats::fitPpca(mesh, clampLatent(options.meshLatentDim, n, mesh.cols()));
    const Eigen::Index qP = m.fp.latentDim(), qV = m.mesh.latentDim();
    Eigen::MatrixXd joined(n, qP + qV);
    joined.leftCols(qP) = stats::latent(m.fp, fp);
    joined.rightCols(qV) = stats::latent(m.mesh, mesh);

    stats::MppcaOptions o;
    o.components = static_cast<int>(std::clamp<Eigen::Index>(options.components, 1, n));
    o.latentDim = static_cast<int>(std::clamp<Eigen::Index>(options.jointLatentDim, 1, qP + qV - 1));
    o.restarts = options.restarts;
    m.joint = stats::fitMppca(joined, o).model;
    prepareMapping(m);
    return m;
}

void prepareMapping(PoseMapping& m)
{
    const Eigen::MatrixXd& W = m.mesh.W;
    const Eigen::MatrixXd WtW = W.transpose() * W;
    Eigen::MatrixXd M = WtW;
    M.diagonal().array() += m.mesh.sigma2;
    // Eq. 4.20 as one matrix; a pseudo-inverse as in stats::fromLatent (zero columns of W).
    m.meshDecoder = W * (WtW.completeOrthogonalDecomposition().pseudoInverse() * M);

    Eigen::MatrixXd Mp = m.fp.W.transpose() * m.fp.W;
    Mp.diagonal().array() += m.fp.sigma2;
    m.fpEncoder = Mp.llt().solve(m.fp.W.transpose());
}

void mapToMesh(const PoseMapping& m, const Eigen::Ref<const Eigen::VectorXd>& fp, Eigen::VectorXd& out)
{
    if (fp.size() != m.fp.dim())
        fail("mapToMesh: an FP pose of ", fp.size(), " values, the mapping takes ", m.fp.dim());
    stats::requireFinite(fp, "mapToMesh: FP pose");
    if (m.meshDecoder.cols() != m.mesh.latentDim() || m.fpEncoder.cols() != m.fp.dim())
        fail("mapToMesh: the mapping is not prepared (prepareMapping)");
    const Eigen::Index qP = m.fp.latentDim();
    const Eigen::VectorXd zP = m.fpEncoder * (fp - m.fp.mean);
    stats::Observations observed;
    for (Eigen::Index j = 0; j < qP; ++j)
        observed.addCoordinate(j, zP(j));
    const stats::Inference inference = stats::infer(m.joint, observed);
    out.resize(m.mesh.dim());
    out.noalias() = m.meshDecoder * inference.reconstruction.tail(m.mesh.latentDim());
    out += m.mesh.mean;
}

Eigen::VectorXd mapToMesh(const PoseMapping& m, const Eigen::Ref<const Eigen::VectorXd>& fp)
{
    Eigen::VectorXd out;
    mapToMesh(m, fp, out);
    return out;
}

Vertices rbfPose(const Vertices& neutral, const FeaturePoints& fps, const Eigen::Ref<const Eigen::VectorXd>& fp)
{
    if (fp.size() != 3 * fps.size())
        fail("rbfPose: an FP pose of ", fp.size(), " values, expected 3 x ", fps.size(), " feature points");
    stats::requireFinite(fp, "rbfPose: FP pose");
    const Eigen::VectorXd source = fps.gather(neutral);
    const Eigen::VectorXd target = source + fp;
    const registration::RbfWarp warp(asVertices(source), asVertices(target));
    return warp.apply(neutral);
}

} // namespace facesketch::pose

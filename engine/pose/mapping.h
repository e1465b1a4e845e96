#pragma once
// From an FP pose to a mesh pose (thesis 5.4.1), and the RBF deformation it is compared with
// (fig. 5.19).
//
// The statistical mapping Psi: P -> V. PPCA on the FP poses (3F-dimensional) and on the mesh
// poses (3#V-dimensional, through the n by n Gram matrix since 3#V >> n: dual PPCA, thesis
// 4.2.1.5, stats/ppca.h fitPpca) gives every training pose an FP latent vector (q_P values) and a
// mesh latent vector (q_V values, eq. 4.19). A mixture of PPCA is fitted on the joined latents
// (n by q_P + q_V, the "mapping matrix"). To map an FP pose p: its FP latents z_P = latent(p)
// fill the first q_P coordinates of a joined vector, the q_V mesh latents are missing and come
// out as their conditional mean under the most probable component (stats/conditional.h), and the
// mesh pose is rebuilt from them by eq. 4.20. The thesis' "n by 2(q_P + q_V)" mapping matrix is
// read as n by (q_P + q_V): the latents of both sides side by side.
//
// Both sides are displacements from the neutral (pose_data.h), so a mapped pose is added to the
// face being posed, whatever its identity.
//
// Cost of one mapping: O(K (q_P + q_V) q^2) for the conditional, then one 3#V by q_V product
// (the decoder matrix W (W^T W)^{-1} M of eq. 4.20 is formed once by prepareMapping): 0.12 ms
// at 6,118 vertices and under 10 ms at 26,196 on the loaded 2-core machine (BENCHMARKS.md,
// `facesketch bench pose`).
//
// The RBF deformation (thesis 3.2.9, registration/rbf.h): the inverse multiquadric plus affine
// map that takes the face's neutral FPs onto its posed FPs, applied to every vertex of the
// neutral face.

#include "core/mesh.h"
#include "pose/pose_data.h"
#include "stats/mppca.h"
#include "stats/ppca.h"

#include <Eigen/Core>

namespace facesketch::pose {

struct MappingOptions {
    /// Latent dimensions of the FP side q_P and the mesh side q_V (clamped below n and d).
    int fpLatentDim = 16;
    int meshLatentDim = 32;
    /// Components of the mixture on the joined latents, and their latent dimension (clamped
    /// below q_P + q_V).
    int components = 3;
    int jointLatentDim = 16;
    int restarts = 2;
};

struct PoseMapping {
    /// PPCA of the FP poses (d = 3F) and of the mesh poses (d = 3#V).
    stats::Ppca fp;
    stats::Ppca mesh;
    /// Mixture on the joined latents [z_P, z_V] (q_P + q_V dimensions).
    stats::Mppca joint;
    /// Derived by prepareMapping, not stored: 3#V by q_V, fromLatent(mesh, z) = mesh.mean +
    /// meshDecoder z; and the q_P by 3F matrix with latent(fp, p) = fpEncoder (p - fp.mean).
    Eigen::MatrixXd meshDecoder;
    Eigen::MatrixXd fpEncoder;
};

/// Fits the mapping.
/// @param[in] fp    n by 3F FP displacements, mm
/// @param[in] mesh  n by 3#V mesh displacements of the same poses, mm
/// Throws Error if the row counts differ, n < 3, or either holds a NaN.
PoseMapping fitMapping(const Eigen::MatrixXd& fp, const Eigen::MatrixXd& mesh, const MappingOptions& options);

/// Forms the derived matrices of a mapping (after fitting or loading).
void prepareMapping(PoseMapping& mapping);

/// Psi(p): the 3#V mesh displacement (mm) of an FP pose p (3F displacements, mm). Throws Error
/// if p has the wrong size or holds a NaN.
Eigen::VectorXd mapToMesh(const PoseMapping& mapping, const Eigen::Ref<const Eigen::VectorXd>& fp);

/// mapToMesh into `out` (3#V, resized if needed): no allocation once out has its size, for
/// playback.
void mapToMesh(const PoseMapping& mapping, const Eigen::Ref<const Eigen::VectorXd>& fp, Eigen::VectorXd& out);

/// The RBF deformation: the face `neutral` (#V by 3, mm) posed so that its FPs move by `fp`
/// (3F displacements): RbfWarp(neutral FPs, neutral FPs + fp) applied to every vertex. Throws
/// Error if the FP vertices lie outside the face, coincide or lie on one plane (rbf.h).
Vertices rbfPose(const Vertices& neutral, const FeaturePoints& fps, const Eigen::Ref<const Eigen::VectorXd>& fp);

} // namespace facesketch::pose

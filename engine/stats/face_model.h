#pragma once
// The generative face model (thesis 4.2): a segmented face, a mixture of PPCA per segment,
// a dual PPCA per segment for the clean-up, and a mixture over the concatenated segment
// latents that correlates the segments. One call turns a few measured vertices into a whole
// face.
//
// This work is based on:
//   Gunnarsson, "Sketching 3D Faces", 2010: 4.2.2 (segments), 4.2.3 (a mixture per segment,
//   its number of components chosen by likelihood), 4.2.4 (clean-up by projection onto the
//   segment's dual PPCA), 4.2.5 (correlation: a mixture on the concatenated latents, and its
//   four online steps), 4.2.1.6 (conditional inference).
//
// Reconstruction, for measurements y of some vertices (stats/conditional.h):
//   1. each segment holding a measured vertex is inferred from its own measurements under
//      its mixture (the winning component's conditional mean), then cleaned up if asked;
//   2. correlation, one of
//      - Joint (the default, our improvement on the thesis): the correlation mixture composed
//        with every segment's clean-up decoder (eq. 4.20) and the blend is itself a mixture of
//        PPCA over whole faces (`joint`). All measurements condition it at once, and every
//        segment is rebuilt from the winning component (then cleaned up if asked). The thesis'
//        route below trusts a segment's own inference however few of its vertices were
//        measured and passes only its latent on; here a segment with three measured vertices
//        weighs as three vertices, and the measurements of every segment inform every other.
//        On an ICT-FaceKit import observed at one feature region (about 10% of the vertices)
//        this roughly halves the error of the thesis' route (`facesketch eval observe
//        --correlation thesis|joint`, figures in docs/face-model.md);
//      - Thesis (4.2.5's four online steps): the latents of the measured segments under their
//        clean-up PPCA are the known part of a latent vector, the correlation mixture infers
//        the rest, and the unmeasured segments are rebuilt from their latents by eq. 4.20;
//      - Off: an unmeasured segment keeps the mean face;
//   3. the segments are blended with the segmentation's weights (no seams).
// The thesis stored full covariances (338 MB at 863 vertices); this model stores W, mu,
// sigma^2 and priors only.

#include "core/mesh.h"
#include "stats/conditional.h"
#include "stats/head_layout.h"
#include "stats/mppca.h"
#include "stats/ppca.h"
#include "stats/segmentation.h"

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace facesketch::stats {

struct FaceModelOptions {
    SegmentationOptions segmentation;
    /// Candidate numbers of components per segment, chosen by held-out likelihood with
    /// `folds`-fold cross-validation (stats/mppca.h, chooseComponents).
    std::vector<int> components = { 1, 2, 3, 4 };
    int folds = 5;
    /// Latent dimension q of every segment mixture component, clamped to the segment's
    /// dimension and to the smallest cross-validation training set; candidates K that would
    /// leave a component fewer than q + 2 faces of that set are skipped.
    int latentDim = 8;
    /// Latent dimension of each segment's clean-up PPCA at most (clamped to n - 2, leaving
    /// variance for sigma^2). The joint correlation can only express what the clean-up spaces
    /// hold, so this is generous.
    int cleanUpDim = 60;
    /// Each segment's clean-up keeps the fewest latent dimensions that hold this fraction of
    /// the segment's training variance (stats/ppca.h dimensionHolding), at most cleanUpDim; 1
    /// keeps cleanUpDim everywhere (the rule until 6 December). The last 0.05% of a segment's
    /// variance is spread over many directions that few training faces take, and a model that
    /// keeps them has freedom to fit a stroke's noise with. On the synthetic high set (20 to 60
    /// latents per segment instead of 60) strokes read about 0.01 better in every view and a
    /// face comes back from 2% of its vertices a sixth better; on an ICT-FaceKit import (42 to
    /// 60) little changes. A fixed 40 everywhere broke the import's one-region inference
    /// (docs/face-model.md, "The clean-up dimension by variance").
    double cleanUpVariance = 0.9995;
    /// Components and latent dimension of the correlation mixture on the concatenated latents
    /// (the dimension is clamped to n - 2): the latent dimension of the joint whole-face model.
    int correlationComponents = 1;
    int correlationLatentDim = 80;
    /// EM settings shared by all mixtures (components and latentDim are overridden).
    MppcaOptions mppca;
    /// Threads fitting the segments' models (0: one per hardware thread). The model is the
    /// same, byte for byte, for any number.
    int threads = 0;
};

/// One segment's models, over the coordinates segmentCoordinates(segmentation, s).
struct SegmentModel {
    Mppca mixture;
    Ppca cleanUp;
    /// Mean training log-likelihood per face under `mixture`, nats.
    double logLikelihood = 0.0;
    /// Orthonormal basis of span(cleanUp.W), 3|segment| by rank: the clean-up (thesis 4.2.4)
    /// as mu + B B^T (t - mu) in O(d q) per call. Derived by deriveFaceModel.
    Eigen::MatrixXd cleanUpBasis;
};

struct FaceModel {
    /// Triangles of the shared topology (#F by 3) and the mean face, 3#V values.
    Triangles triangles;
    Eigen::VectorXd meanFace;
    Segmentation segmentation;
    std::vector<SegmentModel> segments;
    /// Mixture over the concatenation of every segment's clean-up latent vector.
    Mppca correlation;
    /// The correlation mixture composed with the clean-up decoders and the blend: a mixture of
    /// PPCA over whole faces (3#V values), one component per correlation component. Derived
    /// from the fields above by deriveFaceModel (not stored in the model file).
    Mppca joint;
    /// The rest of the head (eyeballs, teeth, tongue) and its topology; empty (vertexCount 0)
    /// for a skin-only model. Filled by model/head_model.h trainHeadModel; a whole head is
    /// rebuilt from it by model/head_assembly.h.
    HeadLayout head;

    Eigen::Index vertexCount() const { return meanFace.size() / 3; }
};

/// Progress of training: called with a short message and the fraction done in [0, 1].
using TrainProgress = std::function<void(const std::string& what, double fraction)>;

/// Trains the model.
/// @param[in] faces     n by 3#V training faces, one per row, laid out (x0, y0, z0, x1, ...)
///                      in millimetres, all on the topology of `triangles`
/// @param[in] triangles #F by 3 triangles of the shared topology
/// @param[in] noseTip   index of the nose-tip vertex
/// Throws Error naming the row and column of a NaN in faces, or for fewer than 4 faces.
FaceModel trainFaceModel(const Eigen::MatrixXd& faces, const Triangles& triangles, int noseTip, const FaceModelOptions& options = {},
    const TrainProgress& progress = {});

/// How measured segments inform the others (step 2 above).
enum class Correlation { Off, Thesis, Joint };

/// "off", "thesis" or "joint"; parseCorrelation throws Error naming any other text.
const char* correlationName(Correlation correlation);
Correlation parseCorrelation(const std::string& text);

struct ReconstructOptions {
    /// Project every inferred segment onto its clean-up PPCA (thesis 4.2.4).
    bool cleanUp = true;
    /// Infer unmeasured segments from the measured ones (thesis 4.2.5, or jointly).
    Correlation correlation = Correlation::Joint;
};

struct Reconstruction {
    /// The whole face, 3#V values.
    Eigen::VectorXd face;
    /// Per segment, the winning component of its mixture: with correlation Off or Thesis the
    /// one whose conditional explained its measurements best, or -1 if none was measured; with
    /// Joint the most probable one for the rebuilt segment.
    std::vector<int> winners;
    /// With Joint, the winning component of `joint`; otherwise -1.
    int jointWinner = -1;
};

/// Composes model.correlation with the segments' clean-up PPCA and the blend weights into
/// model.joint. For correlation component k with mean m, loadings A and noise tau^2, and
/// segment s with clean-up mean mu_s and decoder D_s = W_s (W_s^T W_s)^+ M_s (eq. 4.20, so
/// that fromLatent(x) = mu_s + D_s x) and noise sigma_s^2, the whole face is
///   t = blend_s(mu_s + D_s (m_s + A_s u)) + noise,   u ~ N(0, I),
/// a PPCA with mean blend_s(mu_s + D_s m_s) and loadings blend_s(D_s A_s). Its isotropic
/// noise is the per-coordinate average of the true one, sigma_s^2 I + tau^2 D_s D_s^T:
///   sum_s (d_s sigma_s^2 + tau^2 |D_s|_F^2) / sum_s d_s.
/// Cost O(d q) per component.
Mppca composeCorrelation(const FaceModel& model);

/// Fills the derived fields, model.joint and every segment's cleanUpBasis, from the stored
/// ones; trainFaceModel and loadFaceModel call it.
void deriveFaceModel(FaceModel& model);

/// A table of the trained model, one line per segment: vertices, mixture components, latent
/// dimension, clean-up dimension and mean training log-likelihood per face (nats); then one
/// line each for the correlation mixture and the joint model.
std::string describe(const FaceModel& model);

/// The most probable face given the measurements (vertex indices are those of the model). The
/// whole head with its rigid parts: model/head_assembly.h reconstructHead.
Reconstruction reconstruct(const FaceModel& model, const Observations& observations, const ReconstructOptions& options = {});

/// The joint model's conditional mean at `vertices` (distinct) only, 3 values each in order: the
/// face step 2's Joint correlation infers there, before the clean-up and the blend. For callers
/// that need the face only where it was measured (the tracking model's robust passes) in
/// O(o q^2 + |vertices| q) instead of reconstruct's O(d q). Without Joint correlation (or a
/// joint model), reconstruct's face at those vertices. Throws Error for a vertex outside the
/// model.
Eigen::VectorXd reconstructAt(
    const FaceModel& model, const Observations& observations, const std::vector<int>& vertices, const ReconstructOptions& options = {});

} // namespace facesketch::stats

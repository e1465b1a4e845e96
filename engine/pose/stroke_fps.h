#pragma once
// Feature points from sketched strokes (thesis 5.3). A stroke drawn on a face to pose it (a lip
// line, a lowered brow) is read as observations of a few of the 32 sketchable MPEG-4 points
// (pose/pose_data.h isSketchable: no tongue, teeth or inner lips).
//
// The clusters (thesis fig. 5.4). For the face being posed, FP k's training positions are the
// face's own neutral FP plus every training FP displacement of k (pose_data.h: poses are learnt
// as displacements from each identity's neutral, so they land on any face). Cluster k is the
// 3D Gaussian of those points: mean and covariance by maximum likelihood, plus minStdMm^2 I.
// The thesis fits a 32-component mixture by EM with each component initialised at its FP's
// mean; here the labels are known, so the complete-data maximum likelihood (each component the
// Gaussian of its own FP's points) is used directly: EM on the pooled points could only let
// overlapping clusters (upper lid and brow, the lips' middles) trade points and stop being one
// FP each. Mixing weights are equal (every FP occurs once per pose).
//
// Reading a set of strokes (world points per stroke, e.g. sketch/projection.h projectStroke):
// 1. For every point x: the component log densities l_k(x), the marginal log p(x) and the
//    posterior responsibilities r_k(x) = exp(l_k - logsumexp l) (eq. 4.8, fig. 5.7).
// 2. A point hits cluster k if k has its highest responsibility and the likelihood is above
//    the threshold: the Mahalanobis distance of x from cluster k is at most maxMahalanobis
//    (p(x | k) >= p(mu_k | k) exp(-maxMahalanobis^2 / 2): one threshold for tight and loose
//    clusters alike).
// 3. Groups (fpGroups(): left brow, upper lip, ...): each stroke is assigned to the group its
//    points hit most (endpoints count endpointWeight times; a hit on an FP that several groups
//    share, a lip or eye corner, is split between them; ties go to the group whose clusters
//    explain all of the stroke's points best, the sum of each point's best log density within
//    the group), and its points may then only map to FPs of that group: responsibilities
//    renormalised over the group, threshold as in 2. A stroke that hits no cluster at all is
//    an error.
// 4. Endpoints carry the feature's boundary (thesis 5.3's two methods): their score is raised
//    by log(endpointWeight), and an endpoint that maps to no FP is moved up to nudgeMm towards
//    each of its group's boundary clusters (lip or eye corners, brow ends); if the moved point
//    hits that cluster (step 2's test, within the group) the endpoint is that FP, at the
//    endpoint's own position (a short stroke means a narrower feature).
// 5. The best point per FP: over all strokes, the point with the highest score
//    l_k(x) (+ log endpointWeight at an endpoint).
// 6. Beyond the thesis: the interior FPs follow the ends. The likeliest point of a cluster
//    along a stroke leans towards the cluster's mean, so a widened smile's lip mid-points were
//    read 1.5 mm towards the rest face. Once the ends are read (the boundary FPs of each
//    group, step 4), every other FP of the group is picked again among the points of its
//    stroke that hit it in step 4, by its density *conditioned on the ends' sketch-plane
//    positions* under the joint Gaussian of all clusters (FpClusters::jointCovariance; the
//    conditional Gaussian of eq. 4.21 with the ends' two plane coordinates each as the
//    observed part). Where a group's ends are not read, step 5's pick stands.
//
// The depth a stroke cannot know (thesis 5.3, fig. 5.8): a point's depth comes from the surface
// it was cast onto, which may show no real pose. poseObservations() therefore passes only the
// FP's sketch-plane coordinates (the view's two screen axes, sketch::viewPlaneRows) to the
// completion, which replaces the depth by its conditional expectation given them under the pose
// mixture (eq. 4.21, stats::Observations::addProjectedVertex), for any view. (A perspective
// view's rays are not quite parallel to its axis: the plane is that of the view's centre.)

#include "core/mesh.h"
#include "pose/pose_data.h"
#include "stats/conditional.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace facesketch::pose {

/// A group of sketchable FPs that one stroke draws (thesis 5.3), with the FPs at its ends.
struct FpGroup {
    std::string name;                  ///< e.g. "upper_lip", "brow_left" (the face's left, +x)
    std::vector<std::string> fps;      ///< FDP names
    std::vector<std::string> boundary; ///< the FPs at the feature's ends (corners, brow ends)
};

/// The groups: brow_left/right (4.x), upper_lid_left/right and lower_lid_left/right (3.x, the
/// eye corners in both lids), upper_lip (8.1, 8.5, 8.6, 8.9, 8.10 and the corners 8.3, 8.4),
/// lower_lip (8.2, 8.7, 8.8 and the corners), nose (9.1, 9.2, 9.3, 9.15), cheek_left/right
/// (5.3, 5.4), chin (2.1, 2.10). Together they hold the 32 sketchable FPs.
const std::vector<FpGroup>& fpGroups();

struct FpClusterOptions {
    /// Added to every cluster's standard deviation in each direction (mm): a stroke is drawn
    /// by hand and cast onto a surface, and some FPs barely move in training.
    double minStdMm = 1.5;
};

/// The stroke-point mixture on one face: one 3D Gaussian per sketchable FP that a group holds.
struct FpClusters {
    std::vector<int> fp;               ///< per cluster: its index in FeaturePoints::names
    std::vector<std::string> names;    ///< per cluster: its FDP name
    std::vector<Eigen::Vector3d> mean; ///< mm, on the face
    std::vector<Eigen::Matrix3d> covariance;
    std::vector<Eigen::Matrix3d> precision;
    std::vector<double> logNormaliser;      ///< -log sqrt(det(2 pi covariance))
    std::vector<std::vector<int>> groups;   ///< per fpGroups() entry: its clusters
    std::vector<std::vector<int>> boundary; ///< per fpGroups() entry: its boundary clusters
    /// The clusters' joint covariance (3K by 3K, cluster order, maximum likelihood over the
    /// training poses, plus minStdMm^2 I): its 3 by 3 diagonal blocks are `covariance`, the
    /// rest says how FPs move together (a smile's corners and lip mid-points). 96 by 96 for
    /// the 32 sketchable FPs, so it is kept dense.
    Eigen::MatrixXd jointCovariance;

    int size() const { return static_cast<int>(mean.size()); }
    /// log N(x | cluster k), in log(1/mm^3).
    double logDensity(int k, const Eigen::Vector3d& x) const;
    /// Mahalanobis distance of x from cluster k.
    double mahalanobis(int k, const Eigen::Vector3d& x) const;
};

/// The clusters for posing `neutral` (#V by 3, mm): FP k's points are neutral's FP k plus
/// every row's displacement of k in `fpTraining` (n by 3F, pose_data.h). Every sketchable FP
/// that a group names must be among `fps`. Throws Error naming the FP or size at fault: a
/// missing sketchable FP, fpTraining with other than 3F columns or fewer than 2 rows, a
/// neutral that lacks an FP's vertex or holds a NaN.
FpClusters fpClusters(
    const FeaturePoints& fps, const Eigen::MatrixXd& fpTraining, const Vertices& neutral, const FpClusterOptions& options = {});

/// One stroke to read: its points in the world (mm), in drawing order, and the sketch plane
/// of its view (2 by 3, orthonormal rows: the screen's x and y axes, sketch::viewPlaneRows).
struct PoseStrokePoints {
    std::vector<Eigen::Vector3d> world;
    Eigen::Matrix<double, 2, 3> plane;
};

struct FpReadingOptions {
    /// The likelihood threshold of step 2. 4, not 3: one Gaussian per FP is dominated by the
    /// many closed-mouth poses, and at 3 an open jaw's lower lip (12 mm down) hits the chin's
    /// cluster instead; measured on the synthetic held-out face, jaw_open from its lip and brow
    /// strokes: 6.45 mm at 3, 4.38 mm at 4 (neutral 7.22 mm), the other poses unchanged
    /// (with the completion of posemodel 7fe5a1f; with today's mixtures and the completion's
    /// reading noise, PoseStrokeOptions::readingNoiseMm, jaw_open is 0.96 mm).
    double maxMahalanobis = 4.0;
    /// >= 1: endpoints' vote and score (steps 3-5). A stroke's ends are where the user put the
    /// feature's ends; at 2 an end more than about 1.2 SD from its cluster's mean lost to an
    /// interior point nearer the mean, so a widened smile's corners were read inwards. Fitted
    /// on the `contour` identities of the 40-identity posed sets (`eval poses --identities
    /// contour --endpoint-weight W`, strokes ratio, synthetic high / low / ICT): 1: 0.456 /
    /// 0.448 / 0.692, 2: 0.435 / 0.421 / 0.660, 4: 0.267 / 0.391 / 0.640, 8: 0.227 / 0.365 /
    /// 0.609, 16: 0.227 / 0.359 / 0.608, 32: 0.227 / 0.359 / 0.656. 8 is the smallest value on
    /// the plateau of all three (docs/posing.md).
    double endpointWeight = 8.0;
    double nudgeMm = 6.0;   ///< how far a missing endpoint may move to a boundary cluster
    bool followEnds = true; ///< step 6 (false: the thesis' pick, step 5 alone)
};

/// An FP found in the strokes.
struct IdentifiedFp {
    int fp = -1;                       ///< index in FeaturePoints::names
    std::string name;                  ///< its FDP name
    Eigen::Vector3d position;          ///< the stroke point, mm (its depth from the surface it was cast on)
    Eigen::Matrix<double, 2, 3> plane; ///< the sketch plane of its stroke
    int stroke = -1;                   ///< which stroke, and which of its points
    int point = -1;
    double score = 0;         ///< log p(x | cluster) (+ log endpointWeight at an endpoint); after
                              ///< step 6, log p(x | cluster, the group's ends)
    bool nudged = false;      ///< an endpoint mapped by moving it towards a boundary cluster
    bool conditioned = false; ///< picked in step 6, given its group's ends
};

struct FpReading {
    std::vector<IdentifiedFp> fps;        ///< at most one per FP, in cluster order
    std::vector<std::string> strokeGroup; ///< per stroke: the group it was assigned to
    std::vector<int> strokeHits;          ///< per stroke: how many of its points hit a cluster
};

/// Steps 1-5 above. Throws Error (before returning anything) naming the stroke if one has no
/// points or a non-finite point, or hits no cluster ("pose stroke 2 hits no feature point
/// cluster: its nearest is 8.3 at Mahalanobis distance 7.1, the threshold is 3"), or for
/// options out of range (maxMahalanobis <= 0, endpointWeight < 1, nudgeMm < 0).
FpReading identifyFps(const FpClusters& clusters, const std::vector<PoseStrokePoints>& strokes, const FpReadingOptions& options = {});

/// The completion's observations of a reading (thesis 5.3, eq. 4.21): for each identified FP,
/// the sketch-plane coordinates of its displacement from the neutral face's FP, so that the
/// completion supplies the depth. `neutral` is the face the strokes were drawn to pose (#V by 3).
stats::Observations poseObservations(const FeaturePoints& fps, const Vertices& neutral, const FpReading& reading);

} // namespace facesketch::pose

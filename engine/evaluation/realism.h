#pragma once
// `facesketch eval realism DATASET --reference REF` (issue 16): how far the faces of one dataset
// are from those of another, usually real faces (an ICT import), in two figures: where the mean
// face sits, and how many independent directions the faces vary along.
//
// Mean face distance. The mean face of each set (the mean of its samples' skin, every role) is
// taken; the data's mean is moved onto the reference's by the least-squares similarity
// (rotation, uniform scale, translation; Umeyama 1991, geometry/similarity.h, in double) on
// their shared *central landmarks*: the landmarks of the groups below that both manifests
// label (obs_l/_r are left out: the generator approximates them at its mask's edge, so they
// are not the same point on both). At least 4 are needed. The *central face region* is the
// part of each surface within `regionRadius` (25 mm) of the reference mean's central
// landmarks, both surfaces in the reference's frame. Distances are **nearest-surface**
// distances (point to triangle, registration/surface_query.h), not distances between
// corresponding landmarks or vertices (the two sets need not share a topology): every central
// vertex of the data's mean to the reference mean's skin, and every central vertex of the
// reference's mean to the data mean's skin. Both directions are pooled, each vertex weighted
// by its area (a third of its triangles' areas), so the figure is a surface integral that does
// not depend on either mesh's resolution: RMS = sqrt(sum w d^2 / sum w), and the 95th
// percentile is the smallest d with at least 95% of the weight at or below it. A vertex whose
// nearest point is on the other skin's boundary edge is beside that skin rather than over it
// (the other mask does not reach there); its area is reported as `uncovered`.
//
// Regions. Each central vertex belongs to the group of its nearest central landmark (in the
// reference's frame), so the groups split the central region:
//   eyes   en, ex, ps, pi         brows  os, mf, g
//   nose   n, s, cs1, prn, sn, al, sbal
//   mouth  ls, sto, li, ch, cph   chin   sl, pg, gn
// (_l and _r for paired names, docs/dataset-format.md).
//
// Enclosed surfaces. A central vertex is *enclosed* when the ray along its outward normal meets
// its own skin again within `enclosedReach` (30 mm): the surface faces back into the face, as
// the insides of the nostrils do (ICT-FaceKit models each nasal vestibule as a closed pocket
// reaching about 11 mm up into the nose) and the inner lips. A face whose skin has no such
// pocket (the generator's was a radial height field until its nostril vestibules) is far from
// those surfaces by construction, so the report also gives the distance with every enclosed
// vertex of either set left out (`open`), and each set's enclosed area. `open` is a diagnostic
// beside the figures above, not a replacement for them (docs/realism.md).
//
// Spectrum. The number of principal components that hold 90, 95 and 99% of a set's shape
// variance, from the singular values of the centred data matrix (samples by 3#V), computed as
// the eigenvalues of its samples-by-samples Gram matrix (never the 3#V by 3#V covariance).
// Coordinates are as stored (no per-face alignment: the face model, stats/face_model.h, learns
// them so). Two versions: `skin` over every skin vertex unweighted (what the face model sees)
// and `central` over the central region's vertices, each weighted by the square root of its
// area so the inner product of two faces approximates the surface integral and the count does
// not depend on the mesh's resolution.
//
// Placement. How far a set's faces move in their own frame: per axis, the standard deviation
// over faces of the centroid of each face's shared central landmarks (those the alignment
// uses). The spectrum takes coordinates as stored, so this drift is variance to it, and in its
// first mode: a set whose faces drift more than real ones spends modes on where they sit
// rather than on their shape (docs/realism.md, "v19": the generator's faces drifted 2.4 mm up
// and down and 3.7 mm in depth until v18, ICT-FaceKit's 1.2 and 1.4 mm).
//
// Asymmetry. The share of a set's shape variation that is antisymmetric, over its central
// region: each face's offset from the set's mean, d_v = x_v - mean_v, splits into a symmetric
// and an antisymmetric part through the mean face's mirror plane (fitted to its "_l" / "_r"
// landmark pairs as sketch/symmetry.h does, R the reflection): a_v = (d_v - R d_p) / 2, p the
// vertex nearest v's mirror image. The share is the sum over faces and central vertices of
// w_v |a_v|^2 over the same sum of w_v |d_v|^2, w_v the vertex's area, so it does not depend on
// the resolution. The partner is the nearest vertex, not sketch/symmetry.h's verified
// involution, because ICT-FaceKit's topology is not mirror-symmetric vertex for vertex (that
// map is refused there); a vertex whose mirror image has no vertex within its mean edge length
// is left out. Real faces are nearly but not quite symmetric (ICT-FaceKit 1.6%; docs/realism.md,
// "Now (4 December, v15)"). A set where fewer than half the central vertices find a partner is
// reported as not measured, with the reason, and the other figures stand.
//
// Bending. Where and how much the surfaces bend, which a distance in millimetres hardly sees (a
// crease 0.5 mm deep, a lattice of shallow bumps; docs/realism.md, "Curvature maps"): the mean
// curvature H = (k1 + k2) / 2 of each mesh (contours/curvature.h: Rusinkiewicz's estimator,
// convex positive), in 1/m, over the central region and each region, area-weighted:
//   - each mean face's RMS of H (the data's aligned into the reference's frame, so a scale
//     difference does not count);
//   - the RMS of H_data - H_reference at the nearest point of the other mean face (H
//     interpolated over the nearest triangle by barycentric coordinates), both directions
//     pooled as the distances are;
//   - each set's spread: per central vertex, the standard deviation over the set's faces (n - 1)
//     of that face's own H at the vertex, pooled as sqrt(sum_v w_v s_v^2 / sum_v w_v), w_v the
//     mean face's vertex area: how much the bending differs from face to face. A generator
//     whose faces vary by many small bumps has a large spread; the data's is scaled into the
//     reference's frame by the alignment's scale. Cost: one curvature estimate per face.
// Curvature depends on the sampling more than positions do (a crease narrower than two edges is
// smoothed away), so compare sets of similar resolution, or read the figures beside those of a
// reference against its own import at the data's resolution (docs/realism.md).
//
// Proportions. How far below the eyes the nose's base and the mouth sit, which neither measure
// above sees: the surfaces slide along one another under a nearest-surface distance, and the
// similarity spreads a misplaced feature over every landmark. On each set's own mean face (no
// alignment), heights along the dataset's up axis from the mean of the four eye corners (en and
// ex of both eyes) down to sn and to the mean of the mouth's corners (ch), each also over the
// biocular width ex-ex. Corners of the skin's openings and the nose's base are the landmarks
// least open to convention (ICT-FaceKit's n is a point on the bridge, not Farkas' nasion;
// docs/realism.md), so no other landmark enters. Until v21 the built-in faces had the mouth's
// corners 0.64 ex-ex below the eyes' and ICT-FaceKit's mean face 0.77.
//
// Units: everything in mm (a manifest in cm or m is scaled on loading), curvature in 1/m.

#include "core/mesh.h"
#include "dataset/dataset.h"

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace facesketch::evaluation {

/// The skin of every sample of one dataset, in mm.
struct FaceSet {
    std::string name;                              ///< for messages (the dataset folder)
    Triangles triangles;                           ///< #F by 3, into the skin's vertices (0-based)
    std::map<std::string, int> landmarks;          ///< name -> skin vertex
    Eigen::MatrixXd shapes;                        ///< #samples by 3#V, rows (x0, y0, z0, x1, ...), mm
    Eigen::Vector3d up = Eigen::Vector3d::UnitY(); ///< the manifest's up axis, a unit vector
};

/// The skin component of every sample of `dataset` (train, contour, test, in manifest order),
/// triangles with all three corners in the skin, landmarks on the skin; scaled to mm. Throws
/// Error naming the folder if it has fewer than 2 samples.
FaceSet loadFaceSet(const dataset::Dataset& dataset);

struct RealismOptions {
    double regionRadius = 25.0;  ///< mm around the central landmarks
    double enclosedReach = 30.0; ///< mm along the normal within which a surface counts as enclosed
};

/// Nearest-surface distances over one part of the central region, both directions pooled.
struct SurfaceDistance {
    std::string region; ///< "all", "eyes", "brows", "nose", "mouth", "chin"
    double area = 0.0;  ///< mm^2 of both surfaces together
    double rms = 0.0;   ///< mm, area-weighted
    double p95 = 0.0;   ///< mm, area-weighted 95th percentile
    double max = 0.0;   ///< mm
};

/// The PCA spectrum of one set.
struct Spectrum {
    int samples = 0;
    int dimensions = 0;            ///< columns of the data matrix (3 x vertices used)
    double totalVariance = 0.0;    ///< sum of squared singular values / (samples - 1), mm^2 (area-weighted: mm^4)
    std::vector<double> variances; ///< per mode, descending, same units
    int modes90 = 0, modes95 = 0, modes99 = 0;
};

/// The antisymmetric share of one set's variation (above).
struct Asymmetry {
    bool measured = false; ///< false when the set's mirror map could not be found (message says why)
    std::string message;
    double share = 0.0;     ///< in [0, 1]
    int pairedVertices = 0; ///< vertices of positive weight with a partner at their mirror image (the rest are left out)
};

/// Bending (above) over one part of the central region; curvature in 1/m.
struct Bending {
    std::string region;                             ///< "all", then each region as SurfaceDistance
    double dataRms = 0.0, referenceRms = 0.0;       ///< RMS of H over each mean face's part, area-weighted
    double differenceRms = 0.0;                     ///< RMS of H_data - H_reference at nearest points, both directions
    double dataSpread = 0.0, referenceSpread = 0.0; ///< face-to-face standard deviation of H, pooled over the part
};

/// Proportions (above) of one set's mean face.
struct Proportions {
    bool measured = false; ///< false when a landmark is missing (message names it)
    std::string message;
    double biocular = 0.0;    ///< ex-ex, mm
    double eyesToSn = 0.0;    ///< mm along up, from the eye corners' mean down to sn
    double eyesToMouth = 0.0; ///< mm along up, down to the mouth corners' mean
};

struct RealismReport {
    std::vector<std::string> landmarks;         ///< the shared central landmarks the alignment used
    double alignmentScale = 1.0;                ///< the similarity's scale, data to reference
    double landmarkRms = 0.0;                   ///< mm, RMS distance of the aligned landmark pairs
    double dataArea = 0.0, referenceArea = 0.0; ///< mm^2 of each central region (reference frame)
    double dataUncovered = 0.0;                 ///< mm^2 of the data's central region off the reference skin
    double referenceUncovered = 0.0;            ///< and the reverse
    std::vector<SurfaceDistance> distances;     ///< "all" first, then each region with area
    double dataEnclosed = 0.0;                  ///< mm^2 of the data's central region that is enclosed
    double referenceEnclosed = 0.0;             ///< and of the reference's
    SurfaceDistance open;                       ///< "open": as "all" without the enclosed vertices of either set
    std::vector<Bending> bending;               ///< "all" first, then each region with area in either set
    Spectrum dataSkin, dataCentral, referenceSkin, referenceCentral;
    Asymmetry dataAsymmetry, referenceAsymmetry; ///< over each set's central region
    /// Placement (above): SD over faces of the shared central landmarks' centroid, x / y / z mm.
    Eigen::Vector3d dataPlacement = Eigen::Vector3d::Zero(), referencePlacement = Eigen::Vector3d::Zero();
    Proportions dataProportions, referenceProportions;
};

/// The measures above, `data` against `reference`. Throws Error naming both sets if they share
/// fewer than 4 central landmarks or either has a non-finite coordinate, and naming the set
/// with fewer than 2 samples or no triangle.
RealismReport evaluateRealism(const FaceSet& data, const FaceSet& reference, const RealismOptions& options = {});

/// The spectrum of `shapes` (#samples by 3#V, rows as FaceSet::shapes) with vertex v's three
/// columns multiplied by sqrt(weights[v]) (weights: #V non-negative values, or empty for all 1):
/// the squared singular values of the weighted, centred data matrix over (samples - 1). A mode
/// count is the smallest k whose leading variances sum to at least that fraction of the total.
/// Throws Error for fewer than 2 samples or a weight count other than #V.
Spectrum shapeSpectrum(const Eigen::MatrixXd& shapes, const Eigen::VectorXd& weights = {});

/// Placement (above): the standard deviation over `set`'s faces (n - 1 in the denominator) of the
/// centroid of `landmarks`, per axis, mm. Throws Error naming the set and the landmark if one is
/// not in the set, and for no landmark or fewer than 2 samples.
Eigen::Vector3d placementSpread(const FaceSet& set, const std::vector<std::string>& landmarks);

/// Proportions (above) of `set`'s mean face. A missing landmark (en_l, en_r, ex_l, ex_r, sn,
/// ch_l, ch_r) is not an error but Proportions::measured false, naming it.
Proportions faceProportions(const FaceSet& set);

/// The antisymmetric share of `set`'s variation (above), each vertex weighted by `weights` (#V
/// non-negative values; 0 leaves a vertex out). Throws Error for a weight count other than #V,
/// a negative or NaN weight, or no positive weight; fewer than half the weighted vertices
/// paired is not an error but Asymmetry::measured false. A set whose faces do not vary has
/// share 0. Cost O(#weighted x #V) distance tests.
Asymmetry antisymmetricShare(const FaceSet& set, const Eigen::VectorXd& weights);

/// Which of `vertices` (indices into mesh.V) are enclosed: the segment from the vertex, along
/// its outward unit normal (geometry/normals.h; counter-clockwise triangles seen from outside),
/// from 0.01 mm to `reach` mm, crosses a triangle of the mesh not incident to the vertex. One
/// flag per entry of `vertices`. Cost: O(#vertices x #F) box tests.
std::vector<char> enclosedVertices(const Mesh& mesh, const std::vector<int>& vertices, double reach);

/// Area of each vertex: a third of the areas of its triangles, mm^2. #V values.
Eigen::VectorXd vertexAreas(const Vertices& V, const Triangles& F);

/// The region group of a landmark name ("eyes" for "en_l"), or "" if it is not central.
std::string landmarkGroup(const std::string& landmark);

} // namespace facesketch::evaluation

#pragma once
// The thesis' proof that contours carry a face (4.5.1): take a held-out face's own contour
// points in a view and rebuild the whole face from them with the face model, three ways:
//   KnownVertex      (4.5.1.1) each point observes its own vertex in 3D;
//   NearestCandidate (4.5.1.2) each point is mapped to the nearest candidate of the training
//                    faces' cloud in screen space and observes that candidate's vertex in 3D;
//   Projected2D      (4.5.1.3) as NearestCandidate, but only the point's 2D position in the
//                    view plane is observed (its depth is left to the model).
// Points mapped to the same vertex are averaged (a coordinate can be measured only once).
// Beyond the thesis, the candidate mappings are refined: the reconstruction's own contour
// candidates in the view are computed, every point is mapped again to the nearest of them (or
// of the cloud, whichever is nearer) and the face rebuilt, `refinements` times. A first
// reconstruction is close enough that its contours carry the right vertex indices where the
// cloud of other faces offers a neighbour's.
// Errors are per-vertex Euclidean distances to the true face, beside the mean face's.

#include "contours/candidates.h"
#include "dataset/manifest.h"
#include "geometry/camera.h"
#include "gpu/device.h"
#include "stats/face_model.h"

#include <string>
#include <vector>

namespace facesketch::evaluation {

enum class ContourMapping { KnownVertex, NearestCandidate, Projected2D };
const char* mappingName(ContourMapping mapping);

/// Everything on the model's topology (vertex v of the model is vertex v of every mesh here).
struct ContourEvalData {
    const stats::FaceModel* model = nullptr;
    std::vector<std::uint32_t> flags; ///< VertexFlag per model vertex (labelled, excluded)
    std::vector<Mesh> candidateFaces; ///< the faces whose contours form the cloud (thesis: 230)
    std::vector<std::string> testNames;
    std::vector<Mesh> testFaces; ///< held-out faces, scored
};

struct ContourEvalOptions {
    std::vector<std::pair<std::string, ViewAngles>> views = { { "front", { 0, 0 } }, { "profile", { 90, 0 } }, { "34", { 45, 0 } } };
    int imageSize = 1024;
    double suggestiveThreshold = ContourParams {}.suggestiveThreshold;
    stats::ReconstructOptions reconstruct;
    int refinements = 3; ///< re-mappings against the reconstruction's own contours (0: the thesis' method)
    /// Outlier trimming after each solve of the candidate mappings: observations whose residual
    /// (3D, or in the view plane for Projected2D) exceeds max(trimFactor x median, trimFloor mm)
    /// are dropped and the face solved again, up to `trim` times (0: none, as the thesis).
    int trim = 2;
    double trimFactor = 3.0;
    double trimFloor = 1.0;
};

struct ContourEvalResult {
    std::string face, view;
    ContourMapping mapping = ContourMapping::KnownVertex;
    int points = 0;                           ///< contour points of the face in the view
    int observedVertices = 0;                 ///< distinct vertices they observed
    double meanError = 0, maxError = 0;       ///< reconstruction, mm
    double meanFaceMean = 0, meanFaceMax = 0; ///< the mean face, mm
    Eigen::VectorXd vertexError;              ///< #V reconstruction errors, mm (for error renders)
    Mesh reconstruction;
};

/// VertexFlag bits of the skin vertices in the model's numbering (skin.begin is vertex 0):
/// the manifest's labelled contour vertices and excluded vertices. Throws Error without "skin".
std::vector<std::uint32_t> skinContourFlags(const dataset::Manifest& manifest);

/// Scores every test face in every view with the three mappings (one result each), using the
/// GPU for the candidate cloud. Throws Error if the data do not share the model's topology.
std::vector<ContourEvalResult> evaluateContours(gpu::Device& device, const ContourEvalData& data, const ContourEvalOptions& options = {});

} // namespace facesketch::evaluation

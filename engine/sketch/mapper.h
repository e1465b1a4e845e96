#pragma once
// Reading a stroke: from the points a user drew in one view to the face model's vertices they
// pin down (thesis 4.4, 4.6, 4.8). One StrokeReader per (model, candidate faces) reads every
// stroke:
//   1. densify and project the stroke onto its surface (sketch/projection.h, 4.1.1);
//   2. build the contour candidate cloud of the stroke's box on the GPU and give every point
//      the candidates within a screen radius scaled by tau and a depth tolerance
//      (sketch/stroke_candidates.h, 4.4, 4.8.5.2);
//   3. map points to candidates with one of four mappers:
//      - Nearest: each point to its nearest candidate; several points on one vertex average
//        (the baseline, and the mapping `eval contours` scores);
//      - Heuristic (4.6.1-4.6.2): the grade of eq. 4.29 (endpoint terms 4.30-4.35, s1 and s2 of
//        4.36-4.37), conditions 1 and 2, optionally times the connectivity factor of 4.9;
//      - Hmm (4.8): initial 4.45, emission 4.46-4.47, transition 4.48-4.53 over the k-ring map
//        (geometry/graph.h, k = 4), Viterbi in log space (sketch/viterbi.h); several points on
//        one state keep the closest (4.8.2);
//      - Simple (4.6.3): each point to the nearest of the current face's own contours.
//      Every mapper adapts the chosen candidate to the stroke in screen space (4.6.2): the
//      observation is the candidate moved along the view plane onto the stroke point, keeping
//      the candidate's depth. By default (MapperParams::acrossStrokeOnly, viewPlaneOnly) only
//      its offset across the stroke in the view plane is pinned; MapperParams::thesis() pins
//      the whole adapted position.
//
// Complexity per stroke of n densified points, each with at most m candidates (m <=
// MapperParams::maxCandidatesPerPoint), over a cloud of M candidates in the box:
//   candidates O(GPU cloud + M + n m log m); nearest and simple O(n); heuristic O(n m);
//   HMM O(n m^2) transitions (each an O(log r) look-up in the ring map, r ~ 61 entries per
//   vertex), never one M x M matrix over the whole box. Memory O(n m) plus one m x m layer.

#include "contours/candidates.h"
#include "core/mesh.h"
#include "gpu/device.h"
#include "sketch/mapper_params.h"
#include "sketch/reading.h"
#include "sketch/stroke.h"
#include "stats/face_model.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace facesketch::sketch {

enum class MapperKind { Nearest, Heuristic, Hmm, Simple };

/// "nearest", "heuristic", "hmm", "simple"; parseMapper throws Error naming other text.
const char* mapperName(MapperKind kind);
MapperKind parseMapper(const std::string& text);

/// Where the current face's own contour candidates may lie (StrokeReader::read): labelled and
/// suggestive ones within `rings` rings (at most the reader's 4) of one of `vertices`; silhouette
/// candidates anywhere, since a silhouette slides over the surface as the face changes. The
/// refinement passes keep to the lines the first reading chose with it (sketch/refine.h): a
/// stroke that runs between two of the face's own lines (an upper lip's border and the lips'
/// meeting line) is not handed to the nearer one point by point.
struct ReadAnchor {
    std::vector<std::uint32_t> vertices;
    int rings = 2;
};

/// One per (model, candidate faces); reused for every stroke. Holds the candidate faces'
/// curvature on the GPU (computed once here, as the thesis' offline pass) and the k-ring map.
class StrokeReader {
public:
    /// candidateFaces share the model's topology (the faces whose contours form the cloud,
    /// thesis: 230); flags holds #V VertexFlag bits (or is empty). Throws Error for a face of
    /// another topology (naming its index) or flags of the wrong size.
    StrokeReader(
        gpu::Device& device, const stats::FaceModel& model, const std::vector<Mesh>& candidateFaces, std::vector<std::uint32_t> flags);
    ~StrokeReader();
    StrokeReader(const StrokeReader&) = delete;
    StrokeReader& operator=(const StrokeReader&) = delete;

    /// Reads one stroke against the current face (on the model's topology). Throws Error
    /// (naming what is wrong) for a stroke that cannot be read: no points, a non-finite
    /// coordinate, a bad view (validateStroke), a face of another topology, a plane seen
    /// edge-on. A stroke that can be read but pins nothing (off screen, over empty background,
    /// a single point with no candidate) returns a reading with no observations and says why
    /// in StrokeReading::message. Never changes any state the caller owns. `anchor`, if given,
    /// limits the current face's own contour candidates (the simple mapper's, and
    /// MapperParams::ownContours'); Error for its rings outside [0, 4] or a vertex outside the
    /// face.
    /// `drawn`, if given, flags (#V) the vertices earlier strokes of a similar view constrain
    /// (TrackingModel::drawnVertices), for MapperParams::drawnSigmaTau; Error for another size.
    StrokeReading read(const Stroke& stroke, const Mesh& currentFace, MapperKind kind, const MapperParams& params = {},
        const ReadAnchor* anchor = nullptr, const std::vector<char>* drawn = nullptr);

    struct Timing {
        double candidatesMs = 0; ///< projection, GPU cloud and per-point sets
        double mappingMs = 0;    ///< the mapper
    };
    Timing lastTiming() const { return timing_; }

    const stats::FaceModel& model() const { return model_; }

private:
    struct Impl;
    const stats::FaceModel& model_;
    std::unique_ptr<Impl> impl_;
    Timing timing_;
};

} // namespace facesketch::sketch

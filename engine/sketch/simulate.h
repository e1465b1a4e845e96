#pragma once
// Simulated strokes: a face's own feature contours and silhouette in one view, drawn as a user
// tracing them would, so stroke reading can be measured without a person (issue 12; the user
// study of thesis 4.11 had people trace target faces).
//
// What is traced, on the face seen from the view (an OrbitView framing the mean face, the view
// a user starts from):
//   - every labelled contour of the dataset (thesis 4.3.3: lips, eyes, brows, nose, ...), split
//     into runs of vertices facing the camera (n . v > `facingMin`), runs shorter than
//     `minLengthPx` dropped;
//   - the silhouette (the zero set of n . v traced across the triangles, contours/contour_lines.h),
//     chained into polylines; the `silhouettes` longest ones of at least `minLengthPx`.
// How each feature polyline becomes strokes, as a hand does:
//   - a few strokes per feature: split at 1 to `maxPieces` points, the pieces overlapping a
//     little;
//   - each piece partial (its ends trimmed by up to `trim` of its length) or overshooting
//     (extended along its end tangents by up to `overshoot` of its length), each end on its own;
//   - resampled unevenly: arc-length steps drawn uniformly in [0.5, 1.5] x `spacingPx`;
//   - wander (`wanderPx`): the whole stroke off the contour by a smooth random offset, as a
//     hand's error is (a lip line drawn a little high at one end, a jaw line that bows out):
//     per stroke a Gaussian process in x and y over the arc length, standard deviation
//     `wanderPx` and correlation length `wanderLengthPx`, sampled by 16 random Fourier
//     features. Jitter averages out over a contour's vertices; wander does not;
//   - jitter: every point moved by N(0, noisePx^2) pixels in x and y;
//   - times at a pen speed of `speedPxPerMs`;
//   - drawn from the contour's last vertex back to its first with probability `reversed`: a
//     hand draws a lip or a jaw line either way, and a dataset's contours all run one way.
// --extreme F (thesis 4.11.2's caricatured strokes): the traced face is mean + F (face - mean),
// so every stroke is pushed F times as far from the mean face.
// Deterministic for a seed.

#include "core/mesh.h"
#include "geometry/camera.h"
#include "sketch/stroke.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace facesketch::sketch {

struct SimulateOptions {
    ViewAngles angles;    ///< the view (front 0,0; profile 90,0; three-quarter 45,0)
    int imageSize = 1024; ///< square viewport, pixels
    double noisePx = 1.0; ///< jitter standard deviation, pixels
    double extreme = 1.0; ///< exaggeration away from the mean face (1: the face itself)
    std::uint64_t seed = 1;
    double spacingPx = 6.0;  ///< mean distance between stroke points, pixels
    int maxPieces = 3;       ///< strokes per feature at most
    double trim = 0.08;      ///< largest fraction of a piece left off at an end
    double overshoot = 0.05; ///< largest fraction of a piece drawn past an end
    double facingMin = 0.15; ///< n . v above which a labelled vertex is visible
    double minLengthPx = 25; ///< features shorter on screen are not traced
    int silhouettes = 2;     ///< longest silhouette chains traced
    double speedPxPerMs = 0.6;
    /// Probability that a stroke is drawn backwards (end to start), in [0, 1].
    double reversed = 0.0;
    double wanderPx = 0.0;        ///< smooth offset's standard deviation, pixels (0: none)
    double wanderLengthPx = 60.0; ///< and its correlation length along the stroke, pixels
};

struct SimulatedStroke {
    Stroke stroke;
    std::string feature; ///< the contour's name, or "silhouette"
    /// The traced face's vertices along the piece the stroke draws, in drawing order (for a
    /// silhouette, the vertex nearest each point of its chain): for diagnoses that give the
    /// tracking model the true contour (evaluation::StrokeOracle::TrueCurve), never read by a
    /// mapper.
    std::vector<int> vertices;
};

struct Simulation {
    std::vector<SimulatedStroke> strokes;
    /// The face the strokes depict (the face itself, or its exaggeration), #V by 3, mm.
    Mesh traced;
};

/// Strokes tracing `face` (#V by 3 on the topology of `meanFace`, mm). `contours` are vertex
/// paths in the face's numbering (a manifest's contours, renumbered to the model); `flags`
/// VertexFlag bits per vertex (or empty; excluded vertices are never traced). Throws Error for
/// meshes of different topologies, a non-finite vertex, a non-positive size, spacing or
/// speed, negative noise or wander, a non-positive wander length, an extreme factor that is not
/// finite or a reversed probability outside [0, 1]. `reversed` and the wander draw from their
/// own random streams: at 0 every other draw is the same as without them.
Simulation simulateStrokes(const Mesh& face, const Mesh& meanFace, const std::map<std::string, std::vector<int>>& contours,
    const std::vector<std::uint32_t>& flags, const SimulateOptions& options);

/// A manifest's contours renumbered into the skin component [begin, end): paths are cut where
/// they leave it.
std::map<std::string, std::vector<int>> skinContours(const std::map<std::string, std::vector<int>>& contours, int begin, int end);

} // namespace facesketch::sketch

#pragma once
// Reading a stroke and applying it, then refining the reading against the face it rebuilt
// (not in the thesis; docs/sketching.md, "Passes that keep to the first reading's lines"
// and "Before: each reading refined against the face it rebuilt").
//
// Why: the first reading (the HMM by default) decides which features a stroke draws from the
// contours of the training faces, and it places the vertices it pins as those faces have them:
// the vertices on a training face's silhouette, the vertex of a training face's lip line under
// each point. The sketched face has its own. Once the first reading has rebuilt the face, the
// rebuilt face's own contours are the better guess, and each refinement pass reads the stroke
// again against them (by default with the simple mapper, 4.6.3: each point to the nearest of
// the current face's own silhouette, suggestive and labelled contours) and replaces the previous
// reading by the new one (the tracking model's undo, then apply). The passes are an iterated
// closest-contour fit: the face's silhouette slides over the surface as the face changes, which
// no fixed choice of vertices can follow. The face's other own lines (labelled, suggestive) are
// read only near the vertices the first reading chose (RefineOptions::anchorRings): the first
// reading decides which line a stroke draws, the passes where on the face that line lies.
//
// Measured (`facesketch eval strokes`, 1 px noise, the HMM first, ratios to the mean face's
// error, front / profile / 34 / all views; when the passes were chosen, on the built-in faces of
// generator v15, 4 December: later versions' figures are in docs/sketching.md and
// docs/realism.md): built-in high set, 20 test faces, 0.560 / 0.481 /
// 0.567 / 0.307 without refinement, 0.558 / 0.439 / 0.412 / 0.293 with two free passes, 0.570 /
// 0.441 / 0.429 / 0.288 anchored; its 48 contour faces 0.618 / 0.525 / 0.517 / 0.337, 0.583 /
// 0.482 / 0.509 / 0.294 and 0.592 / 0.463 / 0.500 / 0.289; ICT-FaceKit import, 20 test faces,
// free passes 0.642 / 0.491 / 0.457 / 0.376, anchored 0.631 / 0.463 / 0.459 / 0.364 (10 of them
// without refinement 0.709 / 0.477 / 0.593 / 0.422, free 0.695 / 0.466 / 0.474 / 0.362).
//
// One stroke stays one entry of the tracking model's history whatever the passes: undoing it
// undoes all of them.

#include "sketch/mapper.h"
#include "sketch/tracking.h"

#include <functional>
#include <optional>

namespace facesketch::sketch {

struct RefineOptions {
    /// Passes after the first reading (0: the first reading alone, as the thesis reads). Two
    /// here: one takes the 34 view from 0.567 to 0.433 and two to 0.412, a third gains 0.005
    /// and costs the front view 0.012 (built-in high set of v15, free passes, docs/sketching.md).
    int passes = 2;
    /// The mapper of the passes; empty: the first reading's own.
    std::optional<MapperKind> mapper = MapperKind::Simple;
    /// The passes read the face's own labelled and suggestive contours only within this many
    /// rings of a vertex the first reading mapped (silhouettes anywhere: ReadAnchor); -1: all
    /// of them. 2 (-1 before 4 December, night): a stroke that runs between two of the face's
    /// own lines stays on the one the first reading chose. Chosen on the 48 contour faces
    /// of v15 (HMM, 1 px: 0.583 / 0.482 / 0.509 / 0.294 -> 0.592 / 0.463 / 0.500 / 0.289, front /
    /// profile / 34 / all); the ICT-FaceKit import agrees (0.642 / 0.491 / 0.457 / 0.376 ->
    /// 0.631 / 0.463 / 0.459 / 0.364; strokes wandering 4 px 0.736 / 0.560 / 0.545 / 0.477 ->
    /// 0.679 / 0.543 / 0.551 / 0.459), the built-in test faces lose 0.012 and 0.017 from the
    /// front and 34 views (docs/sketching.md, "Passes that keep to the first reading's lines").
    int anchorRings = 2;

    /// Throws Error naming a negative or absurd (over 16) pass count, or anchor rings outside
    /// [-1, 4].
    void validate() const;
};

/// What reading and applying one stroke did.
struct ReadResult {
    /// The reading the face now follows: the first, or the last refinement pass that applied.
    /// No observations: nothing was applied and the tracking model is as it was.
    StrokeReading reading;
    int passes = 0;              ///< refinement passes applied
    double readMs = 0;           ///< wall time of all readings
    double applyMs = 0;          ///< wall time of all rebuilds
    StrokeReader::Timing timing; ///< the readings' split of readMs, summed
};

/// Called with each reading before it is applied; may change its observations (evaluation
/// oracles give them the truth). Not called for readings that pin nothing.
using ReadingHook = std::function<void(StrokeReading&)>;

/// Applies `first`, a reading of `stroke` against the tracking model's face, if it pins
/// anything; then up to `refine.passes` times reads the stroke again against the rebuilt face
/// (with refine.mapper, or `kind`, the first reading's mapper; anchored to the first reading's
/// vertices unless refine.anchorRings is -1) and replaces the previous reading by the new one.
/// Throws Error where applying `first` does (TrackingModel::apply), with the tracking model
/// unchanged. A pass whose reading is refused, pins nothing or cannot be applied ends the
/// refinement and leaves the previous reading applied. readMs and timing count the passes
/// only.
/// The vertices earlier strokes drew as seen from `stroke`'s view (TrackingModel::drawnVertices,
/// leaving out stroke `exceptStroke`, 0 for none), or nothing when params.drawnSigmaTau is 0:
/// what StrokeReader::read takes as `drawn`.
std::vector<char> drawnFor(const TrackingModel& tracking, const Stroke& stroke, const MapperParams& params, int exceptStroke);

ReadResult applyAndRefine(StrokeReader& reader, TrackingModel& tracking, const Stroke& stroke, StrokeReading first, MapperKind kind,
    const MapperParams& params, const ApplyOptions& apply, const RefineOptions& refine, const ReadingHook& hook = {});

/// Reads `stroke` against the tracking model's face with `kind`, then applyAndRefine. Throws
/// Error where StrokeReader::read or applying the first reading does, with the tracking model
/// unchanged.
ReadResult readAndApply(StrokeReader& reader, TrackingModel& tracking, const Stroke& stroke, MapperKind kind, const MapperParams& params,
    const ApplyOptions& apply, const RefineOptions& refine, const ReadingHook& hook = {});

} // namespace facesketch::sketch

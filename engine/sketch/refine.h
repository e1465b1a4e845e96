#pragma once
// Reading a stroke and applying it, then refining the reading against the face it rebuilt
// (not in the thesis; docs/sketching.md, "Now: each reading refined against the face it
// rebuilt").
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
// no fixed choice of vertices can follow.
//
// Measured (`facesketch eval strokes`, 1 px noise, the HMM first, ratios to the mean face's
// error, front / profile / 34 / all views): built-in high set, 20 test faces, 0.560 / 0.481 /
// 0.567 / 0.307 without refinement, 0.558 / 0.439 / 0.412 / 0.293 with two passes; its 48
// contour faces 0.618 / 0.525 / 0.517 / 0.337 and 0.583 / 0.482 / 0.509 / 0.294 (the test
// faces' 34 view gains more than most); ICT-FaceKit import, 10 test faces, 0.709 / 0.477 /
// 0.593 / 0.422 and 0.695 / 0.466 / 0.474 / 0.362.
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
    /// and costs the front view 0.012 (built-in high set, docs/sketching.md).
    int passes = 2;
    /// The mapper of the passes; empty: the first reading's own.
    std::optional<MapperKind> mapper = MapperKind::Simple;

    /// Throws Error naming a negative or absurd (over 16) pass count.
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
/// (with refine.mapper, or `kind`, the first reading's mapper) and replaces the previous reading
/// by the new one. Throws Error where applying `first` does (TrackingModel::apply), with the
/// tracking model unchanged. A pass whose reading is refused, pins nothing or cannot be applied
/// ends the refinement and leaves the previous reading applied. readMs and timing count the
/// passes only.
ReadResult applyAndRefine(StrokeReader& reader, TrackingModel& tracking, const Stroke& stroke, StrokeReading first, MapperKind kind,
    const MapperParams& params, const ApplyOptions& apply, const RefineOptions& refine, const ReadingHook& hook = {});

/// Reads `stroke` against the tracking model's face with `kind`, then applyAndRefine. Throws
/// Error where StrokeReader::read or applying the first reading does, with the tracking model
/// unchanged.
ReadResult readAndApply(StrokeReader& reader, TrackingModel& tracking, const Stroke& stroke, MapperKind kind, const MapperParams& params,
    const ApplyOptions& apply, const RefineOptions& refine, const ReadingHook& hook = {});

} // namespace facesketch::sketch

#include "sketch/refine.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "geometry/camera.h"
#include "sketch/stroke_candidates.h"

namespace facesketch::sketch {

void RefineOptions::validate() const
{
    if (passes < 0 || passes > 16)
        fail("refinement: ", passes, " passes is not in [0, 16]");
    if (anchorRings < -1 || anchorRings > 4)
        fail("refinement: anchor rings ", anchorRings, " not in [-1, 4]");
}

std::vector<char> drawnFor(const TrackingModel& tracking, const Stroke& stroke, const MapperParams& params, int exceptStroke)
{
    if (!(params.drawnSigmaTau > 0))
        return {};
    return tracking.drawnVertices(viewAxis(orbitCamera(stroke.view)), exceptStroke);
}

namespace {

// One reading of the stroke against the tracking model's face, timed into `out`, given to the
// hook when it pins anything. `exceptStroke`: the tracking model's stroke that is this stroke's
// own earlier reading (a refinement pass), left out of what was drawn before.
StrokeReading timedRead(StrokeReader& reader, const TrackingModel& tracking, const Stroke& stroke, MapperKind kind,
    const MapperParams& params, const ReadingHook& hook, ReadResult& out, int exceptStroke, const ReadAnchor* anchor = nullptr)
{
    Stopwatch clock;
    const std::vector<char> drawn = drawnFor(tracking, stroke, params, exceptStroke);
    StrokeReading r = reader.read(stroke, tracking.faceMesh(), kind, params, anchor, drawn.empty() ? nullptr : &drawn);
    out.readMs += clock.milliseconds();
    out.timing.candidatesMs += reader.lastTiming().candidatesMs;
    out.timing.mappingMs += reader.lastTiming().mappingMs;
    if (!r.observations.empty() && hook)
        hook(r);
    return r;
}

} // namespace

ReadResult applyAndRefine(StrokeReader& reader, TrackingModel& tracking, const Stroke& stroke, StrokeReading first, MapperKind kind,
    const MapperParams& params, const ApplyOptions& apply, const RefineOptions& refine, const ReadingHook& hook)
{
    refine.validate();
    ReadResult out;
    out.reading = std::move(first);
    if (out.reading.observations.empty())
        return out;
    Stopwatch clock;
    tracking.apply(out.reading, apply);
    out.applyMs += clock.milliseconds();

    const MapperKind again = refine.mapper.value_or(kind);
    ReadAnchor anchor;
    anchor.rings = refine.anchorRings;
    for (const VertexObservation& o : out.reading.observations)
        anchor.vertices.push_back(o.vertex);
    for (int pass = 0; pass < refine.passes; ++pass) {
        StrokeReading next;
        try {
            next = timedRead(
                reader, tracking, stroke, again, params, hook, out, tracking.strokes(), refine.anchorRings >= 0 ? &anchor : nullptr);
        } catch (const Error&) {
            break; // the previous reading stays applied
        }
        if (next.observations.empty())
            break;
        clock.restart();
        tracking.undo();
        try {
            tracking.apply(next, apply);
        } catch (const Error&) {
            tracking.redo(); // apply changed nothing: the previous reading is back
            out.applyMs += clock.milliseconds();
            break;
        }
        out.applyMs += clock.milliseconds();
        out.reading = std::move(next);
        ++out.passes;
    }
    return out;
}

ReadResult readAndApply(StrokeReader& reader, TrackingModel& tracking, const Stroke& stroke, MapperKind kind, const MapperParams& params,
    const ApplyOptions& apply, const RefineOptions& refine, const ReadingHook& hook)
{
    refine.validate();
    ReadResult first;
    StrokeReading reading = timedRead(reader, tracking, stroke, kind, params, hook, first, 0);
    ReadResult out = applyAndRefine(reader, tracking, stroke, std::move(reading), kind, params, apply, refine, hook);
    out.readMs += first.readMs;
    out.timing.candidatesMs += first.timing.candidatesMs;
    out.timing.mappingMs += first.timing.mappingMs;
    return out;
}

} // namespace facesketch::sketch

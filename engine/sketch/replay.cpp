#include "sketch/replay.h"

#include "core/error.h"
#include "core/stopwatch.h"

namespace facesketch::sketch {

SessionReplayer::SessionReplayer(gpu::Device& device, const stats::FaceModel& model, const std::vector<Mesh>& candidateFaces,
    std::vector<std::uint32_t> flags, std::map<std::string, int> landmarks, std::string modelName)
    : model_(model)
    , landmarks_(std::move(landmarks))
    , modelName_(std::move(modelName))
    , reader_(device, model, candidateFaces, std::move(flags))
    , tracking_(model)
{
}

RefineOptions SessionReplayer::refineFor(const StrokeAction& action) const
{
    RefineOptions r = refine_;
    if (!refineForced_) {
        if (action.reading.refinePasses)
            r.passes = *action.reading.refinePasses;
        if (action.reading.refineAnchorRings)
            r.anchorRings = *action.reading.refineAnchorRings;
    }
    r.validate();
    return r;
}

namespace {

// Parameters added to MapperParams after sessions began recording all of them (5 December
// 2026), each with the value that reads a stroke as the releases before it did.
const std::map<std::string, double>& addedLater()
{
    static const std::map<std::string, double> added = { { "drawnSigmaTau", 0.0 } };
    return added;
}

} // namespace

MapperParams SessionReplayer::paramsFor(const StrokeAction& action) const
{
    std::map<std::string, double> values = action.reading.mapperParams;
    // A stroke that recorded every parameter but one added later was read by a release without
    // it: that parameter is off, so the stroke replays to the face it gave then. A partial
    // record (a hand-written session) takes today's defaults for what it leaves out.
    bool everyEarlier = !values.empty();
    for (const auto& [name, value] : mapperParamValues(MapperParams {}))
        everyEarlier = everyEarlier && (values.count(name) || addedLater().count(name));
    if (everyEarlier)
        for (const auto& [name, off] : addedLater())
            values.try_emplace(name, off);
    for (const auto& [name, value] : paramOverrides_)
        values[name] = value;
    return mapperParamsFrom(values);
}

ReplayOutcome SessionReplayer::apply(const StrokeAction& action, std::optional<MapperKind> mapperOverride)
{
    ReplayOutcome out;
    out.mapper = mapperOverride ? *mapperOverride : parseMapper(action.reading.mapper);
    out.refine = refineFor(action);
    out.params = paramsFor(action);
    if (action.reading.symmetry && !mirror_) {
        // Found once, from the mean face (the most symmetric), before anything is read so that a
        // face without a mirror map fails before the stroke changes anything.
        Mesh mean;
        mean.F = model_.triangles;
        mean.V = asVertices(model_.meanFace);
        mirror_ = std::make_unique<MirrorMap>(MirrorMap::find(mean, landmarks_, modelName_ + " mean face"));
        out.mirrorFound = true;
    }
    Stopwatch clock;
    try {
        const std::vector<char> drawn = drawnFor(tracking_, action.stroke, out.params, 0);
        out.reading = reader_.read(action.stroke, tracking_.faceMesh(), out.mapper, out.params, nullptr, drawn.empty() ? nullptr : &drawn);
    } catch (const Error& e) {
        out.kind = ReplayOutcome::Kind::Refused;
        out.error = e.what();
        return out;
    }
    out.readMs = clock.milliseconds();
    out.timing = reader_.lastTiming();
    if (out.reading.observations.empty()) {
        out.kind = ReplayOutcome::Kind::PinsNothing;
        return out;
    }
    ApplyOptions apply;
    apply.correlation = action.reading.correlation;
    apply.mirror = action.reading.symmetry ? mirror_.get() : nullptr;
    ReadResult done = applyAndRefine(reader_, tracking_, action.stroke, std::move(out.reading), out.mapper, out.params, apply, out.refine);
    out.reading = std::move(done.reading);
    out.refinePasses = done.passes;
    out.readMs += done.readMs;
    out.timing.candidatesMs += done.timing.candidatesMs;
    out.timing.mappingMs += done.timing.mappingMs;
    out.applyMs = done.applyMs;
    out.kind = ReplayOutcome::Kind::Applied;
    return out;
}

} // namespace facesketch::sketch

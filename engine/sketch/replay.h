#pragma once
// Applying a session's strokes one at a time: the one code path that `facesketch sketch` and
// the app (`facesketch gui`) share, so that a session replays to the identical face in both
// (docs/session-format.md). Per stroke: read it against the current face with its own mapper
// (or an override) through a StrokeReader (sketch/mapper.h), and, if it pins any vertex, apply
// the reading to the tracking model (sketch/tracking.h) with the stroke's correlation and
// symmetry options, and refine it against the rebuilt face (sketch/refine.h). The mirror map
// (sketch/symmetry.h) is found from the model's mean face the first time a stroke asks for
// symmetry.

#include "gpu/device.h"
#include "sketch/mapper.h"
#include "sketch/refine.h"
#include "sketch/session.h"
#include "sketch/symmetry.h"
#include "sketch/tracking.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace facesketch::sketch {

/// What applying one stroke did.
struct ReplayOutcome {
    enum class Kind {
        Applied,     ///< read and applied: the face changed
        PinsNothing, ///< read, but no vertex observed (reading.message says why); face unchanged
        Refused,     ///< the reader threw (error says why); face unchanged
    };
    Kind kind = Kind::Refused;
    MapperKind mapper = MapperKind::Hmm;
    StrokeReading reading;       ///< empty when refused; when applied, the one the face follows
    int refinePasses = 0;        ///< refinement passes applied (sketch/refine.h)
    RefineOptions refine;        ///< the refinement the stroke was read with (refineFor)
    MapperParams params;         ///< the mapper's parameters it was read with (paramsFor)
    std::string error;           ///< when refused
    double readMs = 0;           ///< wall time of the readings (the first and the refinement passes)
    StrokeReader::Timing timing; ///< the reader's split of readMs
    double applyMs = 0;          ///< wall time of the tracking model's rebuilds (Applied only)
    bool mirrorFound = false;    ///< this stroke found the mirror map (mirror() now holds it)
};

/// One per (model, candidate faces, dataset landmarks); the model must outlive it.
class SessionReplayer {
public:
    /// `candidateFaces` and `flags` as StrokeReader takes them; `landmarks` in the model's
    /// numbering (for the mirror map; may be empty if no stroke asks for symmetry);
    /// `modelName` names the model in errors.
    SessionReplayer(gpu::Device& device, const stats::FaceModel& model, const std::vector<Mesh>& candidateFaces,
        std::vector<std::uint32_t> flags, std::map<std::string, int> landmarks, std::string modelName);

    /// Reads `action` against the current face with `mapperOverride` if given, else the
    /// action's mapper, and applies it when it pins anything (forgetting any undone strokes).
    /// A stroke the reader refuses (facesketch::Error) is reported in the outcome and leaves
    /// everything as it was. Throws Error for an unknown mapper name or parameter (paramsFor),
    /// a mirror map that cannot be found (the face unchanged) or an error of the tracking model
    /// (state unchanged).
    ReplayOutcome apply(const StrokeAction& action, std::optional<MapperKind> mapperOverride = std::nullopt);

    /// The tracking model's undo and redo of applied strokes (false: nothing to undo/redo).
    bool undo() { return tracking_.undo(); }
    bool redo() { return tracking_.redo(); }

    const TrackingModel& tracking() const { return tracking_; }
    /// The current face (#V by 3, mm, the model's topology).
    Mesh face() const { return tracking_.faceMesh(); }
    /// The mirror map, once a symmetric stroke has needed it; nullptr before.
    const MirrorMap* mirror() const { return mirror_.get(); }
    StrokeReader& reader() { return reader_; }
    /// The refinement of every stroke applied from now on, overriding what the strokes
    /// recorded (ReadingOptions::refinePasses, refineAnchorRings). Throws Error for invalid
    /// options, keeping the previous ones.
    void setRefine(const RefineOptions& refine)
    {
        refine.validate();
        refine_ = refine;
        refineForced_ = true;
    }
    /// The refinement `action` is read with: setRefine's if called, else what the stroke
    /// recorded, else RefineOptions{} (the reader's defaults).
    RefineOptions refineFor(const StrokeAction& action) const;
    /// Mapper parameters set on every stroke applied from now on, over what the strokes
    /// recorded (by MapperParams field name, as ReadingOptions::mapperParams): a study of a
    /// session with other parameters. Throws Error naming an unknown parameter or a refused
    /// value, keeping the previous overrides.
    void setMapperParamOverrides(const std::map<std::string, double>& overrides)
    {
        (void)mapperParamsFrom(overrides);
        paramOverrides_ = overrides;
    }
    /// The mapper's parameters `action` is read with: the defaults, with what the stroke
    /// recorded set (ReadingOptions::mapperParams), then the overrides (mapperParamsFrom). A
    /// record of every parameter but some added since (MapperParams::drawnSigmaTau) was written
    /// before they existed: those are off, as the release that wrote it read the stroke.
    /// Throws Error naming a parameter this release does not know or a value it refuses.
    MapperParams paramsFor(const StrokeAction& action) const;

private:
    const stats::FaceModel& model_;
    std::map<std::string, int> landmarks_;
    std::string modelName_;
    StrokeReader reader_;
    TrackingModel tracking_;
    std::unique_ptr<MirrorMap> mirror_;
    RefineOptions refine_;
    bool refineForced_ = false;
    std::map<std::string, double> paramOverrides_;
};

} // namespace facesketch::sketch

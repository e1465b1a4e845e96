#pragma once
// A sketching session on disk (docs/session-format.md): the model and dataset it was drawn
// against and the ordered list of what the user did, so that the interactive app and the CLI
// (`facesketch sketch --session FILE`, `facesketch pose`, `facesketch animate`) replay it to the
// identical face. JSON, "format": "facesketch-session", "version": 3 (versions 1 and 2 still
// load). Version 2 added posing (thesis 5.3-5.5): pose strokes, keyframes and clearing the pose,
// as actions of their own "type" in the same ordered list, and the pose model file, the face to
// pose and the timeline's tension at the top level. Version 3 adds moving and deleting a
// keyframe, so that editing the timeline replays and undoes like everything else.

#include "sketch/stroke.h"

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace facesketch::sketch {

inline constexpr const char* kSessionFormat = "facesketch-session";
inline constexpr int kSessionVersion = 3;
/// The oldest version parseSession still reads.
inline constexpr int kSessionOldestVersion = 1;

/// How one stroke is to be read (thesis 4.6, 4.8) and applied (4.6.4).
struct ReadingOptions {
    /// "nearest", "heuristic", "hmm" or "simple" (sketch/mapper.h parseMapper).
    std::string mapper = "hmm";
    /// Unmeasured segments inferred from the measured ones (thesis 4.2.5, 4.6.4) or left at the
    /// mean face.
    bool correlation = true;
    /// Also mirror the stroke's observations onto the other half of the face (sketch/symmetry.h).
    bool symmetry = false;
    /// The refinement the stroke was read with (sketch/refine.h: passes after the first
    /// reading, and the rings the passes keep to, -1 for none), so that a session replays to
    /// the same face after a release changes the defaults. Absent in sessions written before
    /// 5 December 2026: those strokes are read with the reader's defaults.
    std::optional<int> refinePasses;
    std::optional<int> refineAnchorRings;
    /// The mapper's parameters the stroke was read with, by MapperParams field name
    /// (sketch/mapper_params.h mapperParamValues; flags 0 or 1), for the same reason.
    /// Parameters not named, and all of them in sessions written before they were recorded
    /// (5 December 2026), take the replaying release's defaults.
    std::map<std::string, double> mapperParams;
};

/// The mapper names a session accepts, in the order of MapperKind.
const std::vector<std::string>& sessionMapperNames();

struct StrokeAction {
    Stroke stroke;
    ReadingOptions reading;
};

/// What a posing action does (version 2; thesis 5.5).
enum class PoseActionKind {
    Stroke,   ///< a pose stroke: read for feature points (thesis 5.3), the pose completed from them
    Keyframe, ///< the current completed pose becomes a keyframe at `time`
    Clear,    ///< the pose strokes so far are forgotten: the face is neutral again
    /// (version 3) the keyframe at `time` moves to `to`, keeping its pose
    MoveKeyframe,
    /// (version 3) the keyframe at `time` is removed
    DeleteKeyframe,
};

struct PoseAction {
    PoseActionKind kind = PoseActionKind::Stroke;
    /// Stroke: the pose stroke (its surface gives its points their depth).
    Stroke stroke;
    /// Stroke: complete the pose with the alternative mixture (thesis figs. 5.10, 5.11) instead of
    /// the primary one; the pose after a stroke follows that stroke's choice.
    bool alternative = false;
    /// Keyframe: seconds, >= 0; no two keyframes of a session share a time. MoveKeyframe and
    /// DeleteKeyframe: the time of the keyframe they change, which must exist.
    double time = 0;
    /// MoveKeyframe: the new time, >= 0, no other keyframe's.
    double to = 0;
    /// How many shape strokes (Session::actions) come before this action in the file's one
    /// ordered list; non-decreasing along poseActions.
    int afterStrokes = 0;
};

struct Session {
    /// As written in the file: relative paths are relative to the session file's folder.
    /// Version 1 requires model and dataset; version 2 requires them only if there are shape
    /// strokes (empty paths: absent).
    std::filesystem::path model;
    std::filesystem::path dataset;
    /// Shape strokes, in order.
    std::vector<StrokeAction> actions;
    /// Version 2, optional (empty: absent): the pose model file (`facesketch train-poses`) and
    /// the mesh to pose (else the face the shape strokes build, else the pose model's mean face).
    std::filesystem::path poses;
    std::filesystem::path face;
    /// The timeline's cardinal spline tension in [0, 1] (0: Catmull-Rom; pose/timeline.h).
    double tension = 0;
    /// Pose strokes, keyframes and clears, in order, each placed among the shape strokes.
    std::vector<PoseAction> poseActions;
};

/// Parses a session document. Throws Error "<where>: <JSON path>: <problem>" for any bad field,
/// e.g. "s.json: actions[3].stroke.points[12].x: expected a number, found null": a missing or
/// mistyped field, an unknown key, a wrong format or version, a number that overflows a double
/// (named by its text), times that go backwards, an empty stroke, a bad view (the orbitCamera rule), an
/// unknown surface or mapper; for version 2 also an unknown action type, a keyframe time that
/// is negative or equals an earlier keyframe's ("actions[5].time: 1.5 s is also the time of the
/// keyframe at actions[2]"), a tension outside [0, 1], shape strokes without a model or dataset.
Session parseSession(const std::string& text, const std::string& where);

/// Reads and parses a session file (a truncated or empty file is an error naming the file).
Session loadSession(const std::filesystem::path& path);

/// The model and dataset paths of a session loaded from `sessionFile`, resolved against its
/// folder; throws Error naming the session file and field if the model file or the dataset's
/// manifest.json does not exist.
std::pair<std::filesystem::path, std::filesystem::path> sessionInputs(const Session& session, const std::filesystem::path& sessionFile);

/// `path` as the session file at `sessionFile` means it: relative paths from its folder.
std::filesystem::path sessionPath(const std::filesystem::path& sessionFile, const std::filesystem::path& path);

/// The document for a session (validated as parseSession would; throws Error naming the field).
/// Numbers are written with 17 significant digits, so parseSession(toJson(s)) == s exactly.
std::string sessionToJson(const Session& session);

/// Validates and writes the session atomically (core/atomic_file.h).
void saveSession(const std::filesystem::path& path, const Session& session);

bool operator==(const StrokePoint& a, const StrokePoint& b);
bool operator==(const OrbitView& a, const OrbitView& b);
bool operator==(const Stroke& a, const Stroke& b);
bool operator==(const ReadingOptions& a, const ReadingOptions& b);
bool operator==(const StrokeAction& a, const StrokeAction& b);
bool operator==(const PoseAction& a, const PoseAction& b);
bool operator==(const Session& a, const Session& b);

} // namespace facesketch::sketch

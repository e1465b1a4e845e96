#pragma once
// A sketching session on disk (docs/session-format.md): the model and dataset it was drawn
// against and the ordered list of what the user did, so that the interactive app and the CLI
// (`facesketch sketch --session FILE`) replay it to the identical face. JSON,
// "format": "facesketch-session", "version": 1. Strokes are the only action for now; pose strokes
// and keyframes come with the posing issue (their "type" will tell them apart).

#include "sketch/stroke.h"

#include <filesystem>
#include <string>
#include <vector>

namespace facesketch::sketch {

inline constexpr const char* kSessionFormat = "facesketch-session";
inline constexpr int kSessionVersion = 1;

/// How one stroke is to be read (thesis 4.6, 4.8) and applied (4.6.4).
struct ReadingOptions {
    /// "nearest", "heuristic", "hmm" or "simple" (sketch/mapper.h parseMapper).
    std::string mapper = "hmm";
    /// Unmeasured segments inferred from the measured ones (thesis 4.2.5, 4.6.4) or left at the
    /// mean face.
    bool correlation = true;
    /// Also mirror the stroke's observations onto the other half of the face (sketch/symmetry.h).
    bool symmetry = false;
};

/// The mapper names a session accepts, in the order of MapperKind.
const std::vector<std::string>& sessionMapperNames();

struct StrokeAction {
    Stroke stroke;
    ReadingOptions reading;
};

struct Session {
    /// As written in the file: relative paths are relative to the session file's folder.
    std::filesystem::path model;
    std::filesystem::path dataset;
    std::vector<StrokeAction> actions;
};

/// Parses a session document. Throws Error "<where>: <JSON path>: <problem>" for any bad field,
/// e.g. "s.json: actions[3].stroke.points[12].x: expected a number, found null": a missing or
/// mistyped field, an unknown key, a wrong format or version, a number that overflows a double
/// (named by its text), times that go backwards, an empty stroke, a bad view (the orbitCamera rule), an
/// unknown surface or mapper.
Session parseSession(const std::string& text, const std::string& where);

/// Reads and parses a session file (a truncated or empty file is an error naming the file).
Session loadSession(const std::filesystem::path& path);

/// The model and dataset paths of a session loaded from `sessionFile`, resolved against its
/// folder; throws Error naming the session file and field if the model file or the dataset's
/// manifest.json does not exist.
std::pair<std::filesystem::path, std::filesystem::path> sessionInputs(const Session& session, const std::filesystem::path& sessionFile);

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
bool operator==(const Session& a, const Session& b);

} // namespace facesketch::sketch

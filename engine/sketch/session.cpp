#include "sketch/session.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/limits.h"
#include "sketch/mapper_params.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace facesketch::sketch {

using nlohmann::json;

namespace {

// A JSON value with the path that leads to it, for messages such as
// "actions[3].stroke.points[12].x: not a finite number".
struct Node {
    const json& value;
    std::string path;
    const std::string& where;

    [[noreturn]] void bad(const std::string& problem) const { fail(where, ": ", path.empty() ? "(document)" : path, ": ", problem); }

    std::string child(const std::string& key) const { return path.empty() ? key : path + "." + key; }

    const Node& object(const std::set<std::string>& allowed) const
    {
        if (!value.is_object())
            bad(cat("expected an object, found ", value.type_name()));
        for (const auto& item : value.items())
            if (!allowed.count(item.key()))
                fail(where, ": ", child(item.key()), ": unknown field");
        return *this;
    }

    Node operator[](const std::string& key) const
    {
        if (!value.contains(key))
            fail(where, ": ", child(key), ": missing");
        return { value.at(key), child(key), where };
    }
    bool has(const std::string& key) const { return value.contains(key); }

    Node at(size_t i) const { return { value.at(i), cat(path, "[", i, "]"), where }; }

    size_t arraySize() const
    {
        if (!value.is_array())
            bad(cat("expected an array, found ", value.type_name()));
        return value.size();
    }

    double number() const
    {
        if (!value.is_number())
            bad(cat("expected a number, found ", value.type_name()));
        const double x = value.get<double>();
        if (!std::isfinite(x))
            bad(cat("not a finite number (", x, ")"));
        return x;
    }

    double positive() const
    {
        const double x = number();
        if (!(x > 0))
            bad(cat("must be positive, found ", x));
        return x;
    }

    int integer(int lo, int hi) const
    {
        if (!value.is_number_integer())
            bad(cat("expected an integer, found ", value.is_number() ? value.dump() : value.type_name()));
        const auto x = value.get<long long>();
        if (x < lo || x > hi)
            bad(cat("must lie in [", lo, ", ", hi, "], found ", x));
        return static_cast<int>(x);
    }

    bool boolean() const
    {
        if (!value.is_boolean())
            bad(cat("expected true or false, found ", value.type_name()));
        return value.get<bool>();
    }

    std::string text() const
    {
        if (!value.is_string())
            bad(cat("expected a string, found ", value.type_name()));
        return value.get<std::string>();
    }
};

// Largest viewport side a session accepts: far beyond any screen, small enough that w * h fits.
constexpr int kMaxViewport = 32768;

OrbitView parseView(const Node& n)
{
    n.object({ "target", "azimuth", "elevation", "distance", "projection", "half_height", "fov_y", "near", "far", "width", "height" });
    OrbitView v;
    const Node target = n["target"];
    if (target.arraySize() != 3)
        target.bad(cat("expected 3 numbers (x, y, z in mm), found ", target.value.size()));
    v.target = { target.at(0).number(), target.at(1).number(), target.at(2).number() };
    v.angles.azimuthDeg = n["azimuth"].number();
    v.angles.elevationDeg = n["elevation"].number();
    if (std::abs(v.angles.elevationDeg) > 90)
        n["elevation"].bad(cat("must lie in [-90, 90] degrees, found ", v.angles.elevationDeg));
    v.distance = n["distance"].positive();
    const std::string kind = n["projection"].text();
    if (kind == "orthographic")
        v.kind = Projection::Orthographic;
    else if (kind == "perspective")
        v.kind = Projection::Perspective;
    else
        n["projection"].bad(cat("expected \"orthographic\" or \"perspective\", found \"", kind, "\""));
    v.halfHeight = n["half_height"].positive();
    v.fovY = n["fov_y"].positive();
    if (v.fovY >= 3.14159)
        n["fov_y"].bad(cat("must be below pi radians, found ", v.fovY));
    v.nearPlane = n["near"].positive();
    v.farPlane = n["far"].positive();
    if (v.farPlane <= v.nearPlane)
        n["far"].bad(cat("must exceed near (", v.nearPlane, "), found ", v.farPlane));
    v.width = n["width"].integer(1, kMaxViewport);
    v.height = n["height"].integer(1, kMaxViewport);
    try {
        (void)orbitCamera(v);
    } catch (const Error& e) {
        n.bad(e.what());
    }
    return v;
}

Stroke parseStroke(const Node& n)
{
    n.object({ "points", "view", "surface" });
    Stroke s;
    s.view = parseView(n["view"]);
    const Node surface = n["surface"];
    const std::string surfaceText = surface.text();
    try {
        s.surface = parseSurface(surfaceText);
    } catch (const Error& e) {
        surface.bad(e.what());
    }
    const Node points = n["points"];
    const size_t count = points.arraySize();
    if (count == 0)
        points.bad("a stroke needs at least one point");
    s.points.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const Node p = points.at(i);
        p.object({ "x", "y", "t" });
        StrokePoint q;
        q.x = p["x"].number();
        q.y = p["y"].number();
        if (p.has("t")) {
            q.timeMs = p["t"].number();
            if (*q.timeMs < 0)
                p["t"].bad(cat("a time in ms since the stroke began cannot be negative, found ", *q.timeMs));
            if (i > 0 && s.points.back().timeMs && *q.timeMs < *s.points.back().timeMs)
                p["t"].bad(cat("goes backwards (", *q.timeMs, " after ", *s.points.back().timeMs, ")"));
        }
        if (i > 0 && q.timeMs.has_value() != s.points.front().timeMs.has_value())
            p.bad("either every point of a stroke has a time \"t\" or none has");
        s.points.push_back(q);
    }
    return s;
}

ReadingOptions parseReading(const Node& n)
{
    n.object({ "mapper", "correlation", "symmetry", "refine_passes", "refine_anchor_rings", "mapper_params" });
    ReadingOptions r;
    r.mapper = n["mapper"].text();
    const auto& names = sessionMapperNames();
    if (std::find(names.begin(), names.end(), r.mapper) == names.end())
        n["mapper"].bad(cat("expected nearest, heuristic, hmm or simple, found \"", r.mapper, "\""));
    r.correlation = n["correlation"].boolean();
    r.symmetry = n["symmetry"].boolean();
    // The ranges RefineOptions::validate accepts.
    if (n.has("refine_passes"))
        r.refinePasses = n["refine_passes"].integer(0, 16);
    if (n.has("refine_anchor_rings"))
        r.refineAnchorRings = n["refine_anchor_rings"].integer(-1, 4);
    if (n.has("mapper_params")) {
        const Node params = n["mapper_params"];
        if (!params.value.is_object())
            params.bad(cat("expected an object, found ", params.value.type_name()));
        MapperParams p;
        for (const auto& item : params.value.items()) {
            const Node field = params[item.key()];
            const double value = field.number();
            try {
                setMapperParam(p, item.key(), value);
            } catch (const Error& e) {
                field.bad(e.what());
            }
            r.mapperParams[item.key()] = value;
        }
        try {
            p.validate();
        } catch (const Error& e) {
            params.bad(e.what());
        }
    }
    return r;
}

json viewJson(const OrbitView& v)
{
    return json { { "target", { v.target.x, v.target.y, v.target.z } }, { "azimuth", v.angles.azimuthDeg },
        { "elevation", v.angles.elevationDeg }, { "distance", v.distance },
        { "projection", v.kind == Projection::Orthographic ? "orthographic" : "perspective" }, { "half_height", v.halfHeight },
        { "fov_y", v.fovY }, { "near", v.nearPlane }, { "far", v.farPlane }, { "width", v.width }, { "height", v.height } };
}

} // namespace

const std::vector<std::string>& sessionMapperNames()
{
    static const std::vector<std::string> names = { "nearest", "heuristic", "hmm", "simple" };
    return names;
}

Session parseSession(const std::string& text, const std::string& where)
{
    limits::checkJsonLimits(text, where);
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        // nlohmann's byte offset tells a truncated file (offset at the end) from a typo.
        fail(where, ": not a complete JSON document (", text.size(), " bytes; truncated?): ", e.what());
    } catch (const json::exception& e) {
        // e.g. a number too large for a double ("1e999"): nlohmann names its text, not its path.
        fail(where, ": not a valid session document: ", e.what());
    }
    const Node root { doc, "", where };
    root.object({ "format", "version", "model", "dataset", "actions", "poses", "face", "timeline" });
    const std::string format = root["format"].text();
    if (format != kSessionFormat)
        root["format"].bad(cat("expected \"", kSessionFormat, "\", found \"", format, "\""));
    const Node versionNode = root["version"];
    const long long version = versionNode.value.is_number_integer() ? versionNode.value.get<long long>() : -1;
    if (version < kSessionOldestVersion || version > kSessionVersion)
        versionNode.bad(
            cat("this build reads versions ", kSessionOldestVersion, " to ", kSessionVersion, ", found ", versionNode.value.dump()));
    if (version == 1)
        for (const char* key : { "poses", "face", "timeline" })
            if (root.has(key))
                fail(where, ": ", key, ": unknown field in version 1 (posing came with version 2)");

    Session s;
    // Version 1 always names model and dataset; version 2 only when it has shape strokes (below).
    auto path = [&](const char* key, bool required) -> std::filesystem::path {
        if (!required && !root.has(key))
            return {};
        const std::string text = root[key].text();
        if (text.empty())
            root[key].bad("empty path");
        return text;
    };
    s.model = path("model", version == 1);
    s.dataset = path("dataset", version == 1);
    s.poses = path("poses", false);
    s.face = path("face", false);
    if (root.has("timeline")) {
        const Node timeline = root["timeline"];
        timeline.object({ "tension" });
        s.tension = timeline["tension"].number();
        if (s.tension < 0 || s.tension > 1)
            timeline["tension"].bad(cat("must lie in [0, 1], found ", s.tension));
    }
    const Node actions = root["actions"];
    const size_t count = actions.arraySize();
    std::vector<std::pair<double, size_t>> keyframes;
    for (size_t i = 0; i < count; ++i) {
        const Node a = actions.at(i);
        if (!a.value.is_object())
            a.bad(cat("expected an object, found ", a.value.type_name()));
        const std::string type = a["type"].text();
        if (type == "stroke") {
            a.object({ "type", "stroke", "reading" });
            s.actions.push_back({ parseStroke(a["stroke"]), parseReading(a["reading"]) });
            continue;
        }
        if (version == 1)
            a["type"].bad(cat("expected \"stroke\" (the only action of version 1), found \"", type, "\""));
        PoseAction pose;
        pose.afterStrokes = static_cast<int>(s.actions.size());
        if (type == "pose-stroke") {
            a.object({ "type", "stroke", "reading" });
            pose.kind = PoseActionKind::Stroke;
            pose.stroke = parseStroke(a["stroke"]);
            const Node reading = a["reading"];
            reading.object({ "interpretation" });
            const std::string which = reading["interpretation"].text();
            if (which != "primary" && which != "alternative")
                reading["interpretation"].bad(cat("expected \"primary\" or \"alternative\", found \"", which, "\""));
            pose.alternative = which == "alternative";
        } else if (type == "keyframe") {
            a.object({ "type", "time" });
            pose.kind = PoseActionKind::Keyframe;
            pose.time = a["time"].number();
            if (pose.time < 0)
                a["time"].bad(cat("a keyframe time in seconds cannot be negative, found ", pose.time));
            for (const auto& [t, at] : keyframes)
                if (t == pose.time)
                    a["time"].bad(cat(pose.time, " s is also the time of the keyframe at actions[", at, "]"));
            keyframes.emplace_back(pose.time, i);
        } else if (type == "pose-clear") {
            a.object({ "type" });
            pose.kind = PoseActionKind::Clear;
        } else if (type == "keyframe-move" || type == "keyframe-delete") {
            if (version < 3)
                a["type"].bad(cat("\"", type, "\" came with version 3, this file is version ", version));
            const bool move = type == "keyframe-move";
            if (move)
                a.object({ "type", "time", "to" });
            else
                a.object({ "type", "time" });
            pose.kind = move ? PoseActionKind::MoveKeyframe : PoseActionKind::DeleteKeyframe;
            pose.time = a["time"].number();
            const auto key = std::find_if(keyframes.begin(), keyframes.end(), [&](const auto& k) { return k.first == pose.time; });
            if (key == keyframes.end())
                a["time"].bad(cat("no keyframe at ", pose.time, " s to ", move ? "move" : "delete", " at this point of the session"));
            if (move) {
                pose.to = a["to"].number();
                if (pose.to < 0)
                    a["to"].bad(cat("a keyframe time in seconds cannot be negative, found ", pose.to));
                for (const auto& [t, at] : keyframes)
                    if (t == pose.to && t != pose.time)
                        a["to"].bad(cat(pose.to, " s is also the time of the keyframe at actions[", at, "]"));
                *key = { pose.to, i };
            } else {
                keyframes.erase(key);
            }
        } else {
            a["type"].bad(cat("expected \"stroke\", \"pose-stroke\", \"keyframe\", \"keyframe-move\", \"keyframe-delete\" or "
                              "\"pose-clear\", found \"",
                type, "\""));
        }
        s.poseActions.push_back(std::move(pose));
    }
    if (!s.actions.empty())
        for (const char* key : { "model", "dataset" })
            if (!root.has(key))
                fail(where, ": ", key, ": missing (the session has shape strokes, which need the face model and its dataset)");
    return s;
}

Session loadSession(const std::filesystem::path& path)
{
    return parseSession(limits::readFileLimited(path, limits::kMaxJsonFileBytes, "a session file"), path.string());
}

std::filesystem::path sessionPath(const std::filesystem::path& sessionFile, const std::filesystem::path& path)
{
    return path.is_absolute() ? path : sessionFile.parent_path() / path;
}

std::pair<std::filesystem::path, std::filesystem::path> sessionInputs(const Session& session, const std::filesystem::path& sessionFile)
{
    if (session.model.empty() || session.dataset.empty())
        fail(sessionFile.string(), ": ", session.model.empty() ? "model" : "dataset", ": the session names no ",
            session.model.empty() ? "face model file" : "dataset");
    const std::filesystem::path model = sessionPath(sessionFile, session.model);
    const std::filesystem::path dataset = sessionPath(sessionFile, session.dataset);
    if (!std::filesystem::is_regular_file(model))
        fail(sessionFile.string(), ": model: no model file at ", model.string());
    if (!std::filesystem::is_regular_file(dataset / "manifest.json"))
        fail(sessionFile.string(), ": dataset: no dataset (manifest.json) at ", dataset.string());
    return { model, dataset };
}

std::string sessionToJson(const Session& session)
{
    auto strokeJson = [](const Stroke& stroke) {
        json points = json::array();
        for (const StrokePoint& p : stroke.points) {
            json q { { "x", p.x }, { "y", p.y } };
            if (p.timeMs)
                q["t"] = *p.timeMs;
            points.push_back(std::move(q));
        }
        return json { { "points", std::move(points) }, { "view", viewJson(stroke.view) }, { "surface", surfaceName(stroke.surface) } };
    };
    json actions = json::array();
    std::size_t next = 0; // the next pose action to place
    auto placePoseActions = [&](std::size_t strokesSoFar) {
        for (; next < session.poseActions.size(); ++next) {
            const PoseAction& a = session.poseActions[next];
            if (a.afterStrokes < 0 || static_cast<std::size_t>(a.afterStrokes) > session.actions.size()
                || (next > 0 && a.afterStrokes < session.poseActions[next - 1].afterStrokes))
                fail("session to save: poseActions[", next, "].afterStrokes: ", a.afterStrokes,
                    " does not place it among the shape strokes (0 to ", session.actions.size(), ", never decreasing)");
            if (static_cast<std::size_t>(a.afterStrokes) != strokesSoFar)
                return;
            if (a.kind == PoseActionKind::Stroke)
                actions.push_back({ { "type", "pose-stroke" }, { "stroke", strokeJson(a.stroke) },
                    { "reading", { { "interpretation", a.alternative ? "alternative" : "primary" } } } });
            else if (a.kind == PoseActionKind::Keyframe)
                actions.push_back({ { "type", "keyframe" }, { "time", a.time } });
            else if (a.kind == PoseActionKind::MoveKeyframe)
                actions.push_back({ { "type", "keyframe-move" }, { "time", a.time }, { "to", a.to } });
            else if (a.kind == PoseActionKind::DeleteKeyframe)
                actions.push_back({ { "type", "keyframe-delete" }, { "time", a.time } });
            else
                actions.push_back({ { "type", "pose-clear" } });
        }
    };
    for (std::size_t i = 0; i < session.actions.size(); ++i) {
        placePoseActions(i);
        const StrokeAction& a = session.actions[i];
        json reading { { "mapper", a.reading.mapper }, { "correlation", a.reading.correlation }, { "symmetry", a.reading.symmetry } };
        if (a.reading.refinePasses)
            reading["refine_passes"] = *a.reading.refinePasses;
        if (a.reading.refineAnchorRings)
            reading["refine_anchor_rings"] = *a.reading.refineAnchorRings;
        if (!a.reading.mapperParams.empty())
            reading["mapper_params"] = a.reading.mapperParams;
        actions.push_back({ { "type", "stroke" }, { "stroke", strokeJson(a.stroke) }, { "reading", std::move(reading) } });
    }
    placePoseActions(session.actions.size());
    json doc { { "format", kSessionFormat }, { "version", kSessionVersion }, { "actions", std::move(actions) } };
    for (const auto& [key, path] : { std::pair<const char*, const std::filesystem::path*> { "model", &session.model },
             { "dataset", &session.dataset }, { "poses", &session.poses }, { "face", &session.face } })
        if (!path->empty())
            doc[key] = path->generic_string();
    if (session.tension != 0)
        doc["timeline"] = { { "tension", session.tension } };
    std::string text = doc.dump(1) + "\n";
    // Whatever the caller built must read back: the same checks as loading, before any write.
    const Session back = parseSession(text, "session to save");
    if (!(back == session))
        fail("session to save: does not read back as itself (a pose action placed after more shape strokes than there are?)");
    return text;
}

void saveSession(const std::filesystem::path& path, const Session& session)
{
    const std::string text = sessionToJson(session);
    writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

bool operator==(const StrokePoint& a, const StrokePoint& b)
{
    return a.x == b.x && a.y == b.y && a.timeMs == b.timeMs;
}

bool operator==(const OrbitView& a, const OrbitView& b)
{
    return a.target == b.target && a.angles.azimuthDeg == b.angles.azimuthDeg && a.angles.elevationDeg == b.angles.elevationDeg
        && a.distance == b.distance && a.kind == b.kind && a.halfHeight == b.halfHeight && a.fovY == b.fovY && a.nearPlane == b.nearPlane
        && a.farPlane == b.farPlane && a.width == b.width && a.height == b.height;
}

bool operator==(const Stroke& a, const Stroke& b)
{
    return a.points == b.points && a.view == b.view && a.surface == b.surface;
}

bool operator==(const ReadingOptions& a, const ReadingOptions& b)
{
    return a.mapper == b.mapper && a.correlation == b.correlation && a.symmetry == b.symmetry && a.refinePasses == b.refinePasses
        && a.refineAnchorRings == b.refineAnchorRings && a.mapperParams == b.mapperParams;
}

bool operator==(const StrokeAction& a, const StrokeAction& b)
{
    return a.stroke == b.stroke && a.reading == b.reading;
}

bool operator==(const PoseAction& a, const PoseAction& b)
{
    if (a.kind != b.kind || a.afterStrokes != b.afterStrokes)
        return false;
    if (a.kind == PoseActionKind::Stroke)
        return a.stroke == b.stroke && a.alternative == b.alternative;
    if (a.kind == PoseActionKind::Keyframe || a.kind == PoseActionKind::DeleteKeyframe)
        return a.time == b.time;
    if (a.kind == PoseActionKind::MoveKeyframe)
        return a.time == b.time && a.to == b.to;
    return true;
}

bool operator==(const Session& a, const Session& b)
{
    return a.model == b.model && a.dataset == b.dataset && a.actions == b.actions && a.poses == b.poses && a.face == b.face
        && a.tension == b.tension && a.poseActions == b.poseActions;
}

} // namespace facesketch::sketch

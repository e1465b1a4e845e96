// The session file (docs/session-format.md): exact round trips, atomic saves, and a message
// naming the JSON path of every bad field.
#include "sketch/session.h"

#include "core/error.h"
#include "test_common.h"

#include <cfenv>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

using namespace facesketch;
using namespace facesketch::sketch;
namespace fs = std::filesystem;

namespace {

Session example()
{
    Session s;
    s.model = "faces.model";
    s.dataset = "../data/faces";
    for (int a = 0; a < 3; ++a) {
        StrokeAction action;
        action.stroke.view = frameSphereView({ 0.1, -2.0 / 3.0, 1e-300 }, 101.7, { 45.0 * a, -7.25 }, 1024, 768);
        action.stroke.view.kind = a == 1 ? Projection::Perspective : Projection::Orthographic;
        action.stroke.surface = a == 2 ? Surface::ProfilePlane : Surface::Face;
        for (int i = 0; i < 5; ++i) {
            StrokePoint p;
            p.x = 100.0 / 3.0 + i * 0.1;
            p.y = 512.0 - std::sqrt(2.0) * i;
            if (a != 1)
                p.timeMs = i * 16.6666666666667;
            action.stroke.points.push_back(p);
        }
        action.reading.mapper = sessionMapperNames()[static_cast<size_t>(a)];
        action.reading.correlation = a != 0;
        action.reading.symmetry = a == 2;
        if (a != 0) { // the first stroke as sessions before 5 December 2026 have it
            action.reading.refinePasses = a;
            action.reading.refineAnchorRings = a == 1 ? -1 : 4;
            action.reading.mapperParams
                = { { "sigmaDTau", 0.1 + 0.2 / 3.0 * a }, { "useSkeleton", a == 1 ? 0.0 : 1.0 }, { "maxCandidatesPerPoint", 48.0 * a } };
        }
        s.actions.push_back(action);
    }
    return s;
}

std::string fileText(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The message of parsing `text`, or "" if it parses.
std::string messageOf(const std::string& text)
{
    try {
        (void)parseSession(text, "s.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("session: save and load round trip exactly, and saving again gives the same bytes")
{
    test::TempDir dir;
    const Session s = example();
    saveSession(dir / "s.json", s);
    const Session back = loadSession(dir / "s.json");
    REQUIRE(back == s);
    REQUIRE(back.actions[0].stroke.points[1].x == s.actions[0].stroke.points[1].x);
    REQUIRE(back.actions[0].stroke.view.target.z == 1e-300);
    REQUIRE_FALSE(back.actions[1].stroke.points[0].timeMs.has_value());
    saveSession(dir / "t.json", back);
    REQUIRE(fileText(dir / "s.json") == fileText(dir / "t.json"));
    // Strings hold the field names of docs/session-format.md.
    const auto doc = nlohmann::json::parse(fileText(dir / "s.json"));
    REQUIRE(doc["format"] == "facesketch-session");
    REQUIRE(doc["version"] == kSessionVersion);
    REQUIRE(doc["actions"][2]["stroke"]["surface"] == "profile-plane");
    // The refinement a stroke was read with, where recorded; older strokes leave it out.
    REQUIRE(doc["actions"][1]["reading"]["refine_passes"] == 1);
    REQUIRE(doc["actions"][1]["reading"]["refine_anchor_rings"] == -1);
    REQUIRE_FALSE(doc["actions"][0]["reading"].contains("refine_passes"));
    REQUIRE_FALSE(back.actions[0].reading.refinePasses.has_value());
    REQUIRE(back.actions[2].reading.refineAnchorRings == 4);
    // So are the mapper's parameters, exactly.
    REQUIRE(doc["actions"][2]["reading"]["mapper_params"]["sigmaDTau"] == 0.1 + 0.2 / 3.0 * 2);
    REQUIRE(doc["actions"][1]["reading"]["mapper_params"]["useSkeleton"] == 0.0);
    REQUIRE_FALSE(doc["actions"][0]["reading"].contains("mapper_params"));
    REQUIRE(back.actions[2].reading.mapperParams.at("sigmaDTau") == 0.1 + 0.2 / 3.0 * 2);
    REQUIRE(back.actions[0].reading.mapperParams.empty());
}

TEST_CASE("session: a truncated or empty file names the file")
{
    test::TempDir dir;
    saveSession(dir / "s.json", example());
    const std::string text = fileText(dir / "s.json");
    test::writeText(dir / "cut.json", text.substr(0, text.size() / 2));
    REQUIRE_THROWS_WITH(loadSession(dir / "cut.json"), Catch::Contains("cut.json") && Catch::Contains("truncated"));
    test::writeText(dir / "empty.json", "");
    REQUIRE_THROWS_WITH(loadSession(dir / "empty.json"), Catch::Contains("empty.json"));
    REQUIRE_THROWS_WITH(loadSession(dir / "none.json"), Catch::Contains("none.json") && Catch::Contains("cannot open"));
}

TEST_CASE("session: a wrong format or version is refused")
{
    auto doc = nlohmann::json::parse(sessionToJson(example()));
    doc["version"] = kSessionVersion + 1;
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: version: ") && Catch::Contains(cat("found ", kSessionVersion + 1)));
    doc["version"] = 0;
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: version: ") && Catch::Contains("found 0"));
    doc["version"] = "1";
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: version: "));
    doc["version"] = 1;
    doc["format"] = "facesketch-dataset";
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: format: "));
    doc.erase("format");
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: format: missing"));
    REQUIRE_THAT(messageOf("[1, 2]"), Catch::Contains("expected an object"));
}

TEST_CASE("session: a missing model or dataset is named by sessionInputs")
{
    test::TempDir dir;
    Session s = example();
    saveSession(dir / "s.json", s);
    REQUIRE_THROWS_WITH(sessionInputs(loadSession(dir / "s.json"), dir / "s.json"),
        Catch::Contains("s.json: model: no model file at") && Catch::Contains("faces.model"));
    test::writeText(dir / "faces.model", "x");
    REQUIRE_THROWS_WITH(sessionInputs(loadSession(dir / "s.json"), dir / "s.json"), Catch::Contains("s.json: dataset: no dataset"));
    fs::create_directories(dir / ".." / "data" / "faces");
    s.dataset = "data";
    fs::create_directories(dir / "data");
    test::writeText(dir / "data" / "manifest.json", "{}");
    saveSession(dir / "s.json", s);
    const auto [model, dataset] = sessionInputs(loadSession(dir / "s.json"), dir / "s.json");
    REQUIRE(model == dir / "faces.model");
    REQUIRE(dataset == dir / "data");
}

TEST_CASE("session: every bad field is named by its JSON path")
{
    using nlohmann::json;
    const json good = json::parse(sessionToJson(example()));
    REQUIRE(messageOf(good.dump()).empty());
    struct Case {
        std::string pointer; // where to change the document (JSON pointer)
        json value;
        std::string path; // what the message must name
    };
    const std::vector<Case> cases = {
        { "/model", 3, "model: expected a string" },
        { "/model", "", "model: empty path" },
        { "/dataset", nullptr, "dataset: expected a string" },
        { "/actions", json::object(), "actions: expected an array" },
        { "/actions/1/type", "pose", "actions[1].type: expected \"stroke\"" },
        { "/actions/1/extra", 1, "actions[1].extra: unknown field" },
        { "/actions/1/reading/refine_passes", 17, "actions[1].reading.refine_passes: must lie in [0, 16], found 17" },
        { "/actions/1/reading/refine_passes", 1.5, "actions[1].reading.refine_passes: expected an integer" },
        { "/actions/2/reading/refine_anchor_rings", -2, "actions[2].reading.refine_anchor_rings: must lie in [-1, 4]" },
        { "/actions/1/reading/mapper_params", json::array(), "actions[1].reading.mapper_params: expected an object" },
        { "/actions/1/reading/mapper_params/sigmaD", 1.0, "actions[1].reading.mapper_params.sigmaD: mapper parameter 'sigmaD' is unknown" },
        { "/actions/1/reading/mapper_params/sigmaDTau", "wide", "actions[1].reading.mapper_params.sigmaDTau: expected a number" },
        { "/actions/1/reading/mapper_params/useSkeleton", 0.5,
            "actions[1].reading.mapper_params.useSkeleton: mapper parameter useSkeleton = 0.5 must be 0 or 1" },
        { "/actions/2/reading/mapper_params/maxCandidatesPerPoint", 2.5,
            "actions[2].reading.mapper_params.maxCandidatesPerPoint: mapper parameter maxCandidatesPerPoint = 2.5 must be a whole number" },
        { "/actions/2/reading/mapper_params/sigmaDTau", -1.0,
            "actions[2].reading.mapper_params: mapper parameter sigmaDTau = -1 must be positive" },
        { "/actions/0/stroke/points/1/x", "a", "actions[0].stroke.points[1].x: expected a number" },
        { "/actions/0/stroke/points/1/y", nullptr, "actions[0].stroke.points[1].y: expected a number" },
        { "/actions/0/stroke/points/3/t", -1.0, "actions[0].stroke.points[3].t: a time in ms" },
        { "/actions/0/stroke/points/3/t", 1.0, "actions[0].stroke.points[3].t: goes backwards" },
        { "/actions/1/stroke/points/2/t", 1.0, "actions[1].stroke.points[2]: either every point" },
        { "/actions/0/stroke/points/4/z", 1.0, "actions[0].stroke.points[4].z: unknown field" },
        { "/actions/0/stroke/points", json::array(), "actions[0].stroke.points: a stroke needs at least one point" },
        { "/actions/0/stroke/view/target", json::array({ 1, 2 }), "actions[0].stroke.view.target: expected 3 numbers" },
        { "/actions/0/stroke/view/target/2", "z", "actions[0].stroke.view.target[2]: expected a number" },
        { "/actions/0/stroke/view/azimuth", true, "actions[0].stroke.view.azimuth: expected a number" },
        { "/actions/0/stroke/view/elevation", 95.0, "actions[0].stroke.view.elevation: must lie in [-90, 90]" },
        { "/actions/2/stroke/view/distance", 0.0, "actions[2].stroke.view.distance: must be positive" },
        { "/actions/0/stroke/view/projection", "fisheye", "actions[0].stroke.view.projection: expected \"orthographic\"" },
        { "/actions/0/stroke/view/half_height", -1.0, "actions[0].stroke.view.half_height: must be positive" },
        { "/actions/0/stroke/view/fov_y", 4.0, "actions[0].stroke.view.fov_y: must be below pi" },
        { "/actions/0/stroke/view/near", 0.0, "actions[0].stroke.view.near: must be positive" },
        { "/actions/0/stroke/view/far", 0.5, "actions[0].stroke.view.far: must exceed near" },
        { "/actions/0/stroke/view/width", 0, "actions[0].stroke.view.width: must lie in [1, 32768]" },
        { "/actions/0/stroke/view/height", 7.5, "actions[0].stroke.view.height: expected an integer" },
        { "/actions/0/stroke/surface", "wall", "actions[0].stroke.surface: " },
        { "/actions/0/reading/mapper", "best", "actions[0].reading.mapper: expected nearest" },
        { "/actions/0/reading/correlation", 1, "actions[0].reading.correlation: expected true or false" },
        { "/actions/2/reading/symmetry", "yes", "actions[2].reading.symmetry: expected true or false" },
    };
    for (const Case& c : cases) {
        json doc = good;
        doc[json::json_pointer(c.pointer)] = c.value;
        INFO(c.pointer);
        REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: " + c.path));
    }
    for (const std::string field : { "/actions/0/stroke/view", "/actions/1/reading", "/actions/2/stroke/surface" }) {
        json doc = good;
        doc[json::json_pointer(field.substr(0, field.rfind('/')))].erase(field.substr(field.rfind('/') + 1));
        INFO(field);
        REQUIRE_THAT(messageOf(doc.dump()), Catch::Contains("missing"));
    }
    // Infinity cannot be written in JSON; an overflowing literal is refused with its text.
    std::string text = good.dump();
    const std::string x = "\"x\":" + good["actions"][0]["stroke"]["points"][0]["x"].dump();
    REQUIRE(text.find(x) != std::string::npos);
    text.replace(text.find(x), x.size(), "\"x\":1e999");
    // Parsing the literal overflows inside strtod; the debug test main traps overflow for our
    // own arithmetic, so lift the trap for this parse only.
    const int traps = fegetexcept();
    fedisableexcept(FE_ALL_EXCEPT);
    const std::string overflow = messageOf(text);
    feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(traps);
    REQUIRE_THAT(overflow, Catch::StartsWith("s.json: not a valid session document") && Catch::Contains("1e999"));
}

TEST_CASE("session: saving a bad session throws naming the field and leaves the old file")
{
    test::TempDir dir;
    saveSession(dir / "s.json", example());
    const std::string before = fileText(dir / "s.json");
    Session bad = example();
    bad.actions[1].stroke.points[2].y = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(saveSession(dir / "s.json", bad), Catch::Contains("actions[1].stroke.points[2].y"));
    bad = example();
    bad.actions[0].reading.mapper = "fastest";
    REQUIRE_THROWS_WITH(saveSession(dir / "s.json", bad), Catch::Contains("actions[0].reading.mapper"));
    bad = example();
    bad.actions[0].stroke.view.width = 0;
    REQUIRE_THROWS_WITH(saveSession(dir / "s.json", bad), Catch::Contains("actions[0].stroke.view.width"));
    bad = example();
    bad.actions[1].reading.mapperParams["sigmaQ"] = 1;
    REQUIRE_THROWS_WITH(saveSession(dir / "s.json", bad), Catch::Contains("actions[1].reading.mapper_params.sigmaQ"));
    bad = example();
    bad.actions[2].reading.mapperParams["sigmaC"] = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(saveSession(dir / "s.json", bad), Catch::Contains("actions[2].reading.mapper_params.sigmaC"));
    REQUIRE(fileText(dir / "s.json") == before);
    for (const auto& entry : fs::directory_iterator(dir.path()))
        REQUIRE(entry.path().filename() == "s.json"); // no temporary left behind
}

namespace {

// example() with posing (version 2): actions in the file are
// stroke, pose-stroke, keyframe 0, stroke, stroke, pose-clear, pose-stroke, keyframe 2.5.
Session posingExample()
{
    Session s = example();
    s.poses = "poses.model";
    s.face = "face.ply";
    s.tension = 0.25;
    PoseAction stroke;
    stroke.stroke = s.actions[0].stroke;
    stroke.afterStrokes = 1;
    stroke.alternative = true;
    s.poseActions.push_back(stroke);
    PoseAction key;
    key.kind = PoseActionKind::Keyframe;
    key.afterStrokes = 1;
    s.poseActions.push_back(key);
    PoseAction clear;
    clear.kind = PoseActionKind::Clear;
    clear.afterStrokes = 3;
    s.poseActions.push_back(clear);
    stroke.alternative = false;
    stroke.afterStrokes = 3;
    stroke.stroke = s.actions[1].stroke;
    s.poseActions.push_back(stroke);
    key.time = 2.5;
    key.afterStrokes = 3;
    s.poseActions.push_back(key);
    return s;
}

} // namespace

TEST_CASE("session: pose strokes, keyframes and clears round trip in their place among the shape strokes")
{
    test::TempDir dir;
    const Session s = posingExample();
    saveSession(dir / "s.json", s);
    const Session back = loadSession(dir / "s.json");
    REQUIRE(back == s);
    saveSession(dir / "t.json", back);
    REQUIRE(fileText(dir / "s.json") == fileText(dir / "t.json"));
    const auto doc = nlohmann::json::parse(fileText(dir / "s.json"));
    std::vector<std::string> types;
    for (const auto& a : doc["actions"])
        types.push_back(a["type"]);
    REQUIRE(types
        == std::vector<std::string> { "stroke", "pose-stroke", "keyframe", "stroke", "stroke", "pose-clear", "pose-stroke", "keyframe" });
    REQUIRE(doc["actions"][1]["reading"]["interpretation"] == "alternative");
    REQUIRE(doc["actions"][7]["time"] == 2.5);
    REQUIRE(doc["poses"] == "poses.model");
    REQUIRE(doc["face"] == "face.ply");
    REQUIRE(doc["timeline"]["tension"] == 0.25);
    REQUIRE(sessionPath(dir / "s.json", back.poses) == dir / "poses.model");
    // Posing alone needs no face model: a version 2 session without model and dataset.
    Session posing;
    posing.poses = "/abs/poses.model";
    posing.poseActions = { s.poseActions[0] };
    posing.poseActions[0].afterStrokes = 0;
    REQUIRE(parseSession(sessionToJson(posing), "p.json") == posing);
    REQUIRE(sessionPath(dir / "s.json", posing.poses) == "/abs/poses.model");
}

TEST_CASE("session: a version 1 file still loads, and posing in one is refused")
{
    const std::string v1 = R"({"format": "facesketch-session", "version": 1, "model": "m.model", "dataset": "d",
        "actions": [{"type": "stroke", "stroke": {"points": [{"x": 1, "y": 2}],
            "view": {"target": [0, 0, 0], "azimuth": 0, "elevation": 0, "distance": 300, "projection": "orthographic",
                     "half_height": 100, "fov_y": 0.5, "near": 1, "far": 1000, "width": 64, "height": 64},
            "surface": "face"}, "reading": {"mapper": "hmm", "correlation": true, "symmetry": false}}]})";
    const Session s = parseSession(v1, "old.json");
    REQUIRE(s.actions.size() == 1);
    REQUIRE(s.actions[0].stroke.points[0].y == 2);
    REQUIRE(s.poseActions.empty());
    REQUIRE(s.model == "m.model");
    auto doc = nlohmann::json::parse(v1);
    doc["actions"].push_back({ { "type", "keyframe" }, { "time", 1.0 } });
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: actions[1].type: expected \"stroke\" (the only action of version 1)"));
    doc = nlohmann::json::parse(v1);
    doc["poses"] = "p.model";
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: poses: unknown field in version 1"));
    doc = nlohmann::json::parse(v1);
    doc.erase("model");
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: model: missing"));
}

TEST_CASE("session: bad pose actions are named by their JSON path, and nothing is saved")
{
    using nlohmann::json;
    const json good = json::parse(sessionToJson(posingExample()));
    REQUIRE(messageOf(good.dump()).empty());
    struct Case {
        std::string pointer;
        json value;
        std::string path;
    };
    const std::vector<Case> cases = {
        { "/actions/7/time", 0.0, "actions[7].time: 0 s is also the time of the keyframe at actions[2]" },
        { "/actions/2/time", -1.0, "actions[2].time: a keyframe time in seconds cannot be negative" },
        { "/actions/2/time", "soon", "actions[2].time: expected a number" },
        { "/actions/1/reading/interpretation", "maybe", "actions[1].reading.interpretation: expected \"primary\" or \"alternative\"" },
        { "/actions/1/stroke/points/0/x", nullptr, "actions[1].stroke.points[0].x: expected a number" },
        { "/actions/5/stroke", json::object(), "actions[5].stroke: unknown field" },
        { "/actions/5/type", "pose-undo",
            "actions[5].type: expected \"stroke\", \"pose-stroke\", \"keyframe\", \"keyframe-move\", \"keyframe-delete\" or "
            "\"pose-clear\"" },
        { "/timeline/tension", 1.5, "timeline.tension: must lie in [0, 1]" },
        { "/timeline/speed", 1.0, "timeline.speed: unknown field" },
        { "/poses", "", "poses: empty path" },
        { "/face", 7, "face: expected a string" },
    };
    for (const Case& c : cases) {
        json doc = good;
        doc[json::json_pointer(c.pointer)] = c.value;
        INFO(c.pointer);
        REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: " + c.path));
    }
    json doc = good;
    doc.erase("model");
    REQUIRE_THAT(messageOf(doc.dump()), Catch::StartsWith("s.json: model: missing (the session has shape strokes"));

    test::TempDir dir;
    saveSession(dir / "s.json", posingExample());
    const std::string before = fileText(dir / "s.json");
    Session bad = posingExample();
    bad.poseActions[4].time = 0;
    REQUIRE_THROWS_WITH(saveSession(dir / "s.json", bad), Catch::Contains("time: 0 s is also the time of the keyframe"));
    bad = posingExample();
    bad.poseActions[1].afterStrokes = 0;
    REQUIRE_THROWS_WITH(saveSession(dir / "s.json", bad), Catch::Contains("poseActions[1].afterStrokes: 0"));
    bad = posingExample();
    bad.poseActions[3].stroke.points.clear();
    REQUIRE_THROWS_WITH(saveSession(dir / "s.json", bad), Catch::Contains("actions[6].stroke.points: a stroke needs at least one point"));
    REQUIRE(fileText(dir / "s.json") == before);
}

TEST_CASE("session: keyframe moves and deletes round trip (version 3), and bad ones are named")
{
    using nlohmann::json;
    test::TempDir dir;
    Session s = posingExample(); // keyframes at 0 s and 2.5 s
    PoseAction move;
    move.kind = PoseActionKind::MoveKeyframe;
    move.time = 2.5;
    move.to = 4.0;
    move.afterStrokes = 3;
    PoseAction del;
    del.kind = PoseActionKind::DeleteKeyframe;
    del.time = 0.0;
    del.afterStrokes = 3;
    s.poseActions.push_back(move);
    s.poseActions.push_back(del);
    saveSession(dir / "s.json", s);
    REQUIRE(loadSession(dir / "s.json") == s);
    const json doc = json::parse(fileText(dir / "s.json"));
    REQUIRE(doc["version"] == 3);
    REQUIRE(doc["actions"][8] == json { { "type", "keyframe-move" }, { "time", 2.5 }, { "to", 4.0 } });
    REQUIRE(doc["actions"][9] == json { { "type", "keyframe-delete" }, { "time", 0.0 } });
    // After the move, 2.5 s is free for a new keyframe and 4 s is taken.
    json again = doc;
    again["actions"].push_back({ { "type", "keyframe" }, { "time", 2.5 } });
    REQUIRE(messageOf(again.dump()).empty());
    again["actions"].push_back({ { "type", "keyframe" }, { "time", 4.0 } });
    REQUIRE_THAT(
        messageOf(again.dump()), Catch::StartsWith("s.json: actions[11].time: 4 s is also the time of the keyframe at actions[8]"));
    struct Case {
        std::string pointer;
        json value;
        std::string path;
    };
    const std::vector<Case> cases = {
        { "/actions/8/time", 1.0, "actions[8].time: no keyframe at 1 s to move at this point of the session" },
        { "/actions/9/time", 2.5, "actions[9].time: no keyframe at 2.5 s to delete" },
        { "/actions/8/to", 0.0, "actions[8].to: 0 s is also the time of the keyframe at actions[2]" },
        { "/actions/8/to", -2.0, "actions[8].to: a keyframe time in seconds cannot be negative" },
        { "/actions/9/to", 1.0, "actions[9].to: unknown field" },
        { "/version", 2, "actions[8].type: \"keyframe-move\" came with version 3, this file is version 2" },
    };
    for (const Case& c : cases) {
        json bad = doc;
        bad[json::json_pointer(c.pointer)] = c.value;
        INFO(c.pointer);
        REQUIRE_THAT(messageOf(bad.dump()), Catch::StartsWith("s.json: " + c.path));
    }
    // A move to its own time is allowed (nothing changes).
    json same = doc;
    same["actions"][8]["to"] = 2.5;
    REQUIRE(messageOf(same.dump()).empty());
}

TEST_CASE("session: a deeply nested or 10 MB-string document is refused before parsing, naming the byte")
{
    REQUIRE_THROWS_WITH(parseSession("{\"actions\": " + std::string(1000000, '['), "s.json"),
        Catch::Contains("s.json: byte 75: arrays and objects nested more than 64 deep"));
    REQUIRE_THROWS_WITH(parseSession("{\"model\": \"" + std::string(10 << 20, 'm') + "\"}", "s.json"),
        Catch::Contains("s.json: byte 10: a string longer than 65536 bytes"));
}

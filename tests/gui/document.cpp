// The app's document: strokes through the shared replayer, pose actions through the pose
// editor, undo/redo, save/open, export, autosave and the recovery file.
#include "gui/document.h"

#include "core/error.h"
#include "fixture.h"
#include "io/mesh_io.h"
#include "pose/pose_session.h"
#include "pose_fixture.h"
#include "sketch/simulate.h"
#include "test_common.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>

using namespace facesketch;
using namespace facesketch::gui;

namespace {

std::vector<sketch::StrokeAction> actions()
{
    const auto& w = test::sketchWorld();
    sketch::SimulateOptions o;
    o.imageSize = 600;
    o.noisePx = 0.5;
    std::vector<sketch::StrokeAction> out;
    for (const sketch::SimulatedStroke& s : sketch::simulateStrokes(w.testFaces[1], w.mean, w.contours, w.flags, o).strokes)
        out.push_back({ s.stroke, {} });
    return out;
}

// A folder with the files a session's inputs must name (their contents are not read here).
struct Inputs {
    test::TempDir dir;
    std::filesystem::path model = dir / "faces.model", dataset = dir / "faces";
    Inputs()
    {
        std::filesystem::create_directories(dataset);
        std::ofstream(model) << "x";
        std::ofstream(dataset / "manifest.json") << "{}";
    }
};

bool samePoints(const sketch::Stroke& a, const sketch::Stroke& b)
{
    return std::equal(a.points.begin(), a.points.end(), b.points.begin(), b.points.end(),
        [](const sketch::StrokePoint& p, const sketch::StrokePoint& q) { return p.x == q.x && p.y == q.y; });
}

// Adds the strokes of actions() that are not applied yet, in order, until `n` are applied. A
// stroke already in effect is skipped: drawn again it would read the same, and may leave the face
// as it is.
void addApplied(Document& doc, size_t n)
{
    for (const sketch::StrokeAction& a : actions()) {
        if (doc.appliedCount() == n)
            return;
        const auto& strokes = doc.strokes();
        const auto applied = strokes.begin() + static_cast<long>(doc.appliedCount());
        if (std::any_of(strokes.begin(), applied, [&](const DocumentStroke& s) { return samePoints(s.action.stroke, a.stroke); }))
            continue;
        doc.addStroke(a);
    }
    REQUIRE(doc.appliedCount() == n);
}

} // namespace

TEST_CASE("document: undo and redo of strokes restore the face exactly, a new stroke forgets the undone ones")
{
    const auto& w = test::sketchWorld();
    Inputs in;
    sketch::SessionReplayer replayer(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document doc(replayer, in.model, in.dataset);
    REQUIRE_FALSE(doc.canUndo());
    const Mesh mean = doc.face();
    const std::uint64_t r0 = doc.revision();
    addApplied(doc, 1);
    const Mesh one = doc.face();
    const std::uint64_t r1 = doc.revision();
    addApplied(doc, 2);
    const Mesh two = doc.face();
    REQUIRE(two.V != one.V);
    REQUIRE(doc.undo());
    REQUIRE(doc.face().V == one.V);
    REQUIRE(doc.revision() == r1);
    REQUIRE(doc.undo());
    REQUIRE(doc.face().V == mean.V);
    REQUIRE(doc.revision() == r0);
    REQUIRE_FALSE(doc.undo());
    REQUIRE(doc.redo());
    REQUIRE(doc.redo());
    REQUIRE(doc.face().V == two.V);
    REQUIRE_FALSE(doc.redo());
    REQUIRE(doc.strokes().size() == 2);
    REQUIRE(doc.session().actions.size() == 2);
    // Each stroke records the refinement and the mapper's parameters it was read with, so the
    // session replays to this face after the defaults change.
    for (const sketch::StrokeAction& a : doc.session().actions) {
        REQUIRE(a.reading.refinePasses == sketch::RefineOptions {}.passes);
        REQUIRE(a.reading.refineAnchorRings == sketch::RefineOptions {}.anchorRings);
        REQUIRE(a.reading.mapperParams == sketch::mapperParamValues(sketch::MapperParams {}));
    }

    REQUIRE(doc.undo());
    REQUIRE(doc.canRedo());
    const sketch::StrokeAction third = actions().back();
    if (doc.addStroke(third).kind == sketch::ReplayOutcome::Kind::Applied) {
        REQUIRE_FALSE(doc.canRedo());
        REQUIRE(doc.strokes().size() == 2);
        sketch::StrokeAction kept = third; // as given, with the refinement and parameters it was read with
        kept.reading.refinePasses = sketch::RefineOptions {}.passes;
        kept.reading.refineAnchorRings = sketch::RefineOptions {}.anchorRings;
        kept.reading.mapperParams = sketch::mapperParamValues(sketch::MapperParams {});
        REQUIRE(sketch::operator==(doc.strokes().back().action, kept));
        REQUIRE(doc.revision() != r1);
    }
}

TEST_CASE("document: a saved session opens to the identical strokes and face, with paths relative to it")
{
    const auto& w = test::sketchWorld();
    Inputs in;
    sketch::SessionReplayer a(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document doc(a, in.model, in.dataset);
    addApplied(doc, 3);
    doc.undo();
    const std::filesystem::path file = in.dir / "my.session.json";
    doc.save(file);
    const sketch::Session onDisk = sketch::loadSession(file);
    REQUIRE(onDisk.model == "faces.model");
    REQUIRE(onDisk.dataset == "faces");
    REQUIRE(onDisk.actions.size() == 2);

    sketch::SessionReplayer b(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document other(b, in.model, in.dataset);
    REQUIRE(other.open(file) == 0);
    REQUIRE(other.face().V == doc.face().V);
    REQUIRE(sketch::operator==(other.session(), doc.session()));

    // Saved elsewhere, the paths are absolute and the session still opens.
    test::TempDir elsewhere;
    doc.save(elsewhere / "s.json");
    REQUIRE(sketch::loadSession(elsewhere / "s.json").model == in.model);
    REQUIRE(other.open(elsewhere / "s.json") == 0);
    REQUIRE(other.face().V == doc.face().V);
}

namespace {

sketch::PoseAction poseStroke(const std::string& pose, const std::string& contour)
{
    const auto& pw = test::poseWorld();
    return test::strokeAction(test::traceStroke(pw.pose(pose), pw.topology.labels.contours.at(contour), pw.front));
}

} // namespace

TEST_CASE(
    "document: pose actions and shape strokes interleave, undo and redo exactly, and a saved session replays in facesketch pose's editor")
{
    const auto& w = test::sketchWorld();
    const auto& pw = test::poseWorld();
    Inputs in;
    sketch::SessionReplayer replayer(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document doc(replayer, in.model, in.dataset);
    REQUIRE_THROWS_AS(doc.addPoseAction(test::keyframeAction(0)), Error); // no pose model yet
    REQUIRE_FALSE(doc.canUndo());
    const std::filesystem::path poses = in.dir / "p.poses";
    std::ofstream(poses) << "x";
    // The head to pose follows the shape strokes, as the app's does (here: 0.2 % wider per stroke).
    auto headOf = [&](const Document& d) {
        Mesh head = pw.neutral;
        head.V.col(0) *= 1.0 + 0.002 * static_cast<double>(d.appliedCount());
        return head;
    };
    doc.enablePosing(pw.model, poses, [&] { return headOf(doc); });
    addApplied(doc, 2);
    doc.undo(); // an undone stroke, forgotten by the first pose action

    doc.addPoseAction(test::keyframeAction(0));
    REQUIRE(doc.appliedCount() == 1);
    REQUIRE(doc.strokes().size() == 1);
    const std::uint64_t r1 = doc.revision();
    // The neutral as a face file holds it (float32).
    REQUIRE(doc.poseEditor()->neutral().V == headOf(doc).V.cast<float>().cast<double>());
    doc.addPoseAction(poseStroke("smile_open", "lip_upper_outer"));
    const Vertices smiled = doc.poseEditor()->face().V;
    REQUIRE((smiled - doc.poseEditor()->neutral().V).rowwise().norm().maxCoeff() > 1.0);
    doc.addPoseAction(test::keyframeAction(1));
    REQUIRE(doc.poseEditor()->keyframes().size() == 2);

    // A shape stroke while the face is posed reshapes the head, and the same pose actions pose the
    // new head (as a fresh editor replaying them does); undo gives back the old posed face exactly.
    const std::uint64_t r3 = doc.revision();
    const Vertices head1 = doc.poseEditor()->neutral().V;
    const std::vector<sketch::StrokeAction> more = actions();
    for (size_t k = 1; doc.appliedCount() == 1; ++k)
        doc.addStroke(more.at(k));
    REQUIRE(doc.poseAppliedCount() == 3);
    REQUIRE(doc.poseEditor()->keyframes().size() == 2);
    REQUIRE(doc.poseEditor()->neutral().V == headOf(doc).V.cast<float>().cast<double>());
    REQUIRE(doc.poseEditor()->neutral().V != head1);
    const Vertices smiledWider = doc.poseEditor()->face().V;
    {
        pose::PoseEditor fresh(pw.model, doc.poseEditor()->neutral());
        for (const sketch::PoseAction& a : doc.poseActions())
            fresh.apply(a);
        REQUIRE(fresh.face().V == smiledWider);
    }
    const std::uint64_t r4 = doc.revision();
    REQUIRE(doc.undo());
    REQUIRE(doc.appliedCount() == 1);
    REQUIRE(doc.revision() == r3);
    REQUIRE(doc.poseEditor()->face().V == smiled);
    REQUIRE(doc.poseEditor()->keyframes().size() == 2);

    // Undo goes back through the history in order, redo forward again.
    REQUIRE(doc.undo());
    REQUIRE(doc.undo());
    REQUIRE(doc.poseEditor()->face().V == doc.poseEditor()->neutral().V);
    REQUIRE(doc.revision() == r1);
    REQUIRE(doc.undo());
    REQUIRE(doc.undo());
    REQUIRE(doc.appliedCount() == 0);
    REQUIRE_FALSE(doc.undo());
    for (int i = 0; i < 4; ++i)
        REQUIRE(doc.redo());
    REQUIRE(doc.poseEditor()->face().V == smiled);
    REQUIRE(doc.revision() == r3);
    REQUIRE(doc.redo()); // the shape stroke drawn after the pose actions
    REQUIRE_FALSE(doc.redo());
    REQUIRE(doc.poseEditor()->face().V == smiledWider);
    REQUIRE(doc.revision() == r4);

    // Saved: the session names the pose model and a face file; `facesketch pose` poses that file
    // with the session's actions to the identical face, and the document opens it again.
    const std::filesystem::path file = in.dir / "posed.json";
    doc.save(file);
    const sketch::Session onDisk = sketch::loadSession(file);
    REQUIRE(onDisk.poses == "p.poses");
    REQUIRE(onDisk.face == "posed.face.ply");
    REQUIRE(onDisk.actions.size() == 2);
    REQUIRE(onDisk.poseActions.size() == 3);
    REQUIRE(onDisk.poseActions[2].afterStrokes == 1); // before the second stroke, in the file's order
    pose::PoseEditor cli(pw.model, readMesh(in.dir / "posed.face.ply"));
    pose::replayPoseActions(cli, onDisk);
    REQUIRE(cli.face().V == smiledWider);

    sketch::SessionReplayer b(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document other(b, in.model, in.dataset);
    REQUIRE_THROWS_AS(other.open(file), Error); // pose actions, but no pose model
    REQUIRE(other.appliedCount() == 0);
    other.enablePosing(pw.model, poses, [&] { return headOf(other); });
    REQUIRE(other.open(file) == 0);
    REQUIRE(other.poseAppliedCount() == 3);
    REQUIRE(other.poseEditor()->face().V == smiledWider);
    REQUIRE(sketch::operator==(other.session(), doc.session()));
    // The opened history is the file's order: the shape stroke is undone first.
    REQUIRE(other.undo());
    REQUIRE(other.appliedCount() == 1);
    REQUIRE(other.poseEditor()->face().V == smiled);
    REQUIRE(other.undo());
    REQUIRE(other.poseEditor()->keyframes().size() == 1);
    // Opened again over this work (two actions undone), the open undoes to the work as it was
    // posed, its undone actions redo, then the open again.
    const Vertices workFace = other.poseEditor()->face().V;
    const size_t workPoses = other.poseAppliedCount();
    REQUIRE(other.open(file) == 0);
    REQUIRE(other.poseEditor()->face().V == smiledWider);
    REQUIRE(other.undoReopens());
    REQUIRE(other.undo());
    REQUIRE(other.poseAppliedCount() == workPoses);
    REQUIRE(other.poseEditor()->face().V == workFace);
    REQUIRE(other.redo());
    REQUIRE(other.redo());
    REQUIRE(other.poseEditor()->face().V == smiledWider);
    REQUIRE(other.redoReopens());
    REQUIRE(other.redo());
    REQUIRE(other.poseEditor()->face().V == smiledWider);
    REQUIRE(sketch::operator==(other.session(), doc.session()));

    // Export writes the posed face.
    doc.exportMesh(in.dir / "posed.ply");
    REQUIRE((readMesh(in.dir / "posed.ply").V - smiledWider).cwiseAbs().maxCoeff() < 1e-4);
}

TEST_CASE("document: opening a session over work is one action, undone to the work exactly and redone")
{
    const auto& w = test::sketchWorld();
    Inputs in;
    // The session to open: one stroke, drawn by another document.
    sketch::SessionReplayer b(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document other(b, in.model, in.dataset);
    addApplied(other, 1);
    const std::filesystem::path file = in.dir / "one.session.json";
    other.save(file);

    // The work: three strokes, the last one undone (to be redone).
    sketch::SessionReplayer a(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document doc(a, in.model, in.dataset);
    addApplied(doc, 3);
    REQUIRE(doc.undo());
    const Mesh work = doc.face();
    const sketch::Session workSession = doc.session();
    const std::uint64_t workRevision = doc.revision();
    REQUIRE(work.V != other.face().V);
    REQUIRE_FALSE(doc.undoReopens());

    REQUIRE(doc.open(file) == 0);
    REQUIRE(doc.face().V == other.face().V);
    REQUIRE(doc.appliedCount() == 1);
    REQUIRE_FALSE(doc.canRedo()); // (the work's undone stroke comes back with the work)
    REQUIRE(doc.undoReopens());
    // One undo brings the work back as it was: strokes in effect, the undone one, the face.
    REQUIRE(doc.undo());
    REQUIRE(doc.face().V == work.V);
    REQUIRE(sketch::operator==(doc.session(), workSession));
    REQUIRE(doc.strokes().size() == 3);
    REQUIRE(doc.appliedCount() == 2);
    REQUIRE(doc.revision() == workRevision);
    REQUIRE_FALSE(doc.undoReopens());
    // Redo: first the work's undone stroke, then the open again.
    REQUIRE(doc.redo());
    REQUIRE(doc.appliedCount() == 3);
    const Mesh workAll = doc.face();
    REQUIRE(doc.redoReopens());
    REQUIRE(doc.redo());
    REQUIRE(doc.face().V == other.face().V);
    REQUIRE(sketch::operator==(doc.session(), other.session()));
    REQUIRE_FALSE(doc.canRedo());

    // A stroke on the opened session undoes one by one down to the open, then the open goes.
    addApplied(doc, 2);
    REQUIRE_FALSE(doc.undoReopens());
    REQUIRE(doc.undo());
    REQUIRE(doc.face().V == other.face().V);
    REQUIRE(doc.undoReopens());
    REQUIRE(doc.undo());
    REQUIRE(doc.face().V == workAll.V);
    REQUIRE(doc.appliedCount() == 3);
    // The work's own history is still there; a new action forgets the undone open.
    REQUIRE(doc.undo());
    REQUIRE(doc.face().V == work.V);
    REQUIRE(doc.canRedo());
    doc.addStroke(doc.strokes()[2].action);
    REQUIRE(doc.appliedCount() == 3);
    REQUIRE_FALSE(doc.canRedo());

    // An open that fails changes nothing, undone strokes included.
    REQUIRE(doc.undo());
    test::writeText(in.dir / "cut.json", "{\"format\": \"facesketch-session\", \"vers");
    REQUIRE_THROWS_AS(doc.open(in.dir / "cut.json"), Error);
    // (its first stroke is applied before the second's unknown mapper throws)
    sketch::Session broken = other.session();
    broken.actions.push_back(broken.actions.front());
    broken.actions.back().reading.mapper = "nope";
    REQUIRE_THROWS_WITH(doc.load(broken, in.dir / "x.json", "x.json"), Catch::Contains("nope"));
    REQUIRE(doc.face().V == work.V);
    REQUIRE(doc.appliedCount() == 2);
    REQUIRE(doc.redo());
    REQUIRE(doc.appliedCount() == 3);
}

TEST_CASE("document: a session of another model or a broken file is refused and changes nothing")
{
    const auto& w = test::sketchWorld();
    Inputs in, second;
    sketch::SessionReplayer a(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document doc(a, in.model, in.dataset);
    addApplied(doc, 1);
    const Mesh before = doc.face();

    sketch::SessionReplayer b(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document foreign(b, second.model, second.dataset);
    foreign.save(second.dir / "foreign.json");
    REQUIRE_THROWS_WITH(doc.open(second.dir / "foreign.json"), Catch::Contains("foreign.json: model: drawn against"));
    test::writeText(in.dir / "cut.json", "{\"format\": \"facesketch-session\", \"vers");
    REQUIRE_THROWS_AS(doc.open(in.dir / "cut.json"), Error);
    REQUIRE(doc.face().V == before.V);
    REQUIRE(doc.appliedCount() == 1);
    REQUIRE(doc.undo());
}

TEST_CASE("document: export writes the face as PLY or OBJ and refuses other formats")
{
    const auto& w = test::sketchWorld();
    Inputs in;
    sketch::SessionReplayer a(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document doc(a, in.model, in.dataset);
    addApplied(doc, 1);
    for (const char* name : { "face.ply", "face.obj" }) {
        doc.exportMesh(in.dir / name);
        const Mesh back = readMesh(in.dir / name);
        REQUIRE(back.F == doc.face().F);
        REQUIRE((back.V - doc.face().V).cwiseAbs().maxCoeff() < 1e-5);
    }
    REQUIRE_THROWS_WITH(doc.exportMesh(in.dir / "face.stl"), Catch::Contains("face.stl: export writes .obj or .ply"));
    REQUIRE_FALSE(std::filesystem::exists(in.dir / "face.stl"));
}

TEST_CASE("autosave: saves changes once per interval and on flush, and the recovery file restores every stroke")
{
    const auto& w = test::sketchWorld();
    Inputs in;
    sketch::SessionReplayer a(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document doc(a, in.model, in.dataset);
    const std::filesystem::path file = in.dir / "state" / "recovery-session.json";
    Autosave autosave(file, 30, doc.revision());
    REQUIRE_FALSE(autosave.tick(doc, 100)); // starts the clock
    REQUIRE_FALSE(autosave.tick(doc, 200)); // nothing changed
    REQUIRE_FALSE(autosave.flush(doc));
    REQUIRE_FALSE(std::filesystem::exists(file));
    addApplied(doc, 2);
    REQUIRE_FALSE(autosave.tick(doc, 129)); // 29 s since the last save time
    REQUIRE(autosave.tick(doc, 231));
    REQUIRE(autosave.saves() == 1);
    REQUIRE_FALSE(autosave.tick(doc, 300)); // unchanged
    addApplied(doc, 3);
    REQUIRE_FALSE(autosave.tick(doc, 250));
    REQUIRE(autosave.flush(doc)); // on exit
    REQUIRE(autosave.saves() == 2);

    sketch::SessionReplayer b(test::device(), w.model, w.candidateFaces, w.flags, {}, "model");
    Document restored(b, in.model, in.dataset);
    REQUIRE(restored.open(file) == 0);
    REQUIRE(restored.appliedCount() == 3);
    REQUIRE(restored.face().V == doc.face().V);

    // An unwritable place: kept as an error, never thrown.
    test::writeText(in.dir / "blocker", "a file, not a folder");
    Autosave broken(in.dir / "blocker" / "recovery.json", 1, 0);
    REQUIRE_FALSE(broken.flush(doc));
    REQUIRE_FALSE(broken.lastError().empty());
    REQUIRE_THROWS_WITH(Autosave(file, 0, 0), Catch::Contains("interval"));

    // Turned off (no file, as for a benchmark): a changed document is never written, no error.
    const auto before = std::filesystem::last_write_time(file);
    Autosave off({}, 1, 0);
    REQUIRE_FALSE(off.tick(doc, 0));
    REQUIRE_FALSE(off.tick(doc, 10));
    REQUIRE_FALSE(off.flush(doc));
    REQUIRE(off.saves() == 0);
    REQUIRE(off.lastError().empty());
    REQUIRE(std::filesystem::last_write_time(file) == before);
}

TEST_CASE("autosave: the recovery file lies under FACESKETCH_STATE_DIR, XDG_STATE_HOME or ~/.local/state")
{
    const std::string oldHome = std::getenv("HOME") ? std::getenv("HOME") : "";
    ::unsetenv("FACESKETCH_STATE_DIR");
    ::unsetenv("XDG_STATE_HOME");
    ::setenv("HOME", "/home/someone", 1);
    REQUIRE(recoveryFile() == "/home/someone/.local/state/facesketch/recovery-session.json");
    ::setenv("XDG_STATE_HOME", "/x/state", 1);
    REQUIRE(recoveryFile() == "/x/state/facesketch/recovery-session.json");
    ::setenv("FACESKETCH_STATE_DIR", "/tmp/fs", 1);
    REQUIRE(recoveryFile() == "/tmp/fs/recovery-session.json");
    ::unsetenv("FACESKETCH_STATE_DIR");
    ::unsetenv("XDG_STATE_HOME");
    ::setenv("HOME", oldHome.c_str(), 1);
}

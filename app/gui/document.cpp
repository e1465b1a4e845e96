#include "gui/document.h"

#include "core/error.h"
#include "io/mesh_io.h"

#include <algorithm>
#include <cstdlib>

namespace facesketch::gui {

namespace {

std::filesystem::path absoluteNormal(const std::filesystem::path& p)
{
    return std::filesystem::absolute(p).lexically_normal();
}

// Relative to `folder` when inside it (a session moved with its data still opens), else absolute.
std::filesystem::path relativeIfInside(const std::filesystem::path& p, const std::filesystem::path& folder)
{
    const std::filesystem::path rel = p.lexically_relative(folder);
    if (rel.empty() || *rel.begin() == "..")
        return p;
    return rel;
}

bool samePath(const std::filesystem::path& a, const std::filesystem::path& b)
{
    std::error_code ec;
    if (std::filesystem::equivalent(a, b, ec))
        return true;
    return absoluteNormal(a) == absoluteNormal(b);
}

} // namespace

Document::Document(sketch::SessionReplayer& replayer, const std::filesystem::path& model, const std::filesystem::path& dataset)
    : replayer_(replayer)
    , model_(absoluteNormal(model))
    , dataset_(absoluteNormal(dataset))
{
    if (replayer_.tracking().strokes() != 0)
        fail("gui: the document needs a replayer with no stroke applied");
}

sketch::ReplayOutcome Document::addStroke(sketch::StrokeAction action)
{
    sketch::ReplayOutcome out = replayer_.apply(action);
    if (out.kind != sketch::ReplayOutcome::Kind::Applied)
        return out;
    // The session records the refinement and the mapper's parameters the stroke was read with,
    // so that it replays to this face after a release changes the defaults.
    action.reading.refinePasses = out.refine.passes;
    action.reading.refineAnchorRings = out.refine.anchorRings;
    action.reading.mapperParams = sketch::mapperParamValues(out.params);
    // The replayer forgot its undone strokes when it applied this one, so the document does too.
    dropRedo();
    strokes_.push_back({ std::move(action), out.reading });
    history_.push_back(Step::Shape);
    ++applied_;
    const std::uint64_t previousRevision = revision_;
    revision_ = nextRevision_++;
    revisions_.push_back(revision_);
    shapeRevisions_.push_back(revision_);
    if (poseApplied_ > 0) {
        // The pose actions in effect pose the new neutral. If one cannot (a pose stroke that no
        // longer hits a feature point), the stroke is taken back and the editor kept.
        std::unique_ptr<pose::PoseEditor> before = std::move(editor_);
        const std::uint64_t beforeRevision = editorRevision_;
        try {
            reposeNeutral();
        } catch (...) {
            strokes_.pop_back();
            history_.pop_back();
            revisions_.pop_back();
            shapeRevisions_.pop_back();
            --applied_;
            revision_ = previousRevision;
            replayer_.undo();
            editor_ = std::move(before);
            editorRevision_ = beforeRevision;
            throw;
        }
    }
    return out;
}

void Document::dropRedo()
{
    reopen_.clear();
    strokes_.resize(applied_);
    poseActions_.resize(poseApplied_);
    history_.resize(done());
    revisions_.resize(done() + 1);
    shapeRevisions_.resize(applied_ + 1);
}

void Document::reposeNeutral()
{
    buildEditor();
    for (size_t i = 0; i < poseApplied_; ++i) {
        try {
            editor_->apply(poseActions_[i]);
        } catch (const Error& e) {
            fail("the new face cannot be posed as before: pose action ", i, ": ", e.what());
        }
    }
}

Document::Snapshot Document::capture()
{
    Snapshot s;
    s.strokes = strokes_;
    s.applied = applied_;
    s.poseActions = poseActions_;
    s.poseApplied = poseApplied_;
    s.history = history_;
    s.tension = tension_;
    s.revisions = revisions_;
    s.shapeRevisions = shapeRevisions_;
    s.revision = revision_;
    s.openBase = openBase_;
    s.editor = std::move(editor_);
    s.editorRevision = editorRevision_;
    return s;
}

void Document::restore(Snapshot&& s)
{
    // Reading is deterministic: the strokes replayed from no stroke give the same faces.
    while (replayer_.undo()) { }
    for (size_t i = 0; i < s.strokes.size(); ++i)
        if (replayer_.apply(s.strokes[i].action).kind != sketch::ReplayOutcome::Kind::Applied)
            fail("gui: stroke ", i, " of the document to restore no longer applies");
    for (size_t i = s.applied; i < s.strokes.size(); ++i)
        replayer_.undo();
    strokes_ = std::move(s.strokes);
    applied_ = s.applied;
    poseActions_ = std::move(s.poseActions);
    poseApplied_ = s.poseApplied;
    history_ = std::move(s.history);
    tension_ = s.tension;
    revisions_ = std::move(s.revisions);
    shapeRevisions_ = std::move(s.shapeRevisions);
    revision_ = s.revision;
    openBase_ = s.openBase;
    editor_ = std::move(s.editor);
    editorRevision_ = s.editorRevision;
    if (poseApplied_ > 0 && (!editor_ || editorRevision_ != shapeRevisions_[applied_]))
        reposeNeutral();
}

bool Document::undo()
{
    if (undoReopens()) {
        Snapshot opened = capture();
        Snapshot previous = std::move(before_.back());
        before_.pop_back();
        restore(std::move(previous));
        reopen_.push_back(std::move(opened));
        return true;
    }
    if (done() <= openBase_)
        return false;
    if (history_[done() - 1] == Step::Pose) {
        if (!editor_ || !editor_->undo())
            return false;
        --poseApplied_;
    } else {
        if (!replayer_.undo())
            return false;
        --applied_;
        // The previous neutral was posed by the same actions, so this cannot fail.
        if (poseApplied_ > 0)
            reposeNeutral();
    }
    revision_ = revisions_[done()];
    return true;
}

bool Document::redo()
{
    if (redoReopens()) {
        Snapshot previous = capture();
        Snapshot opened = std::move(reopen_.back());
        reopen_.pop_back();
        restore(std::move(opened));
        before_.push_back(std::move(previous));
        return true;
    }
    if (done() == history_.size())
        return false;
    if (history_[done()] == Step::Shape) {
        if (!replayer_.redo())
            return false;
        ++applied_;
        if (poseApplied_ > 0)
            reposeNeutral();
    } else {
        // The editor may have been rebuilt for this neutral since the action was undone (its
        // redo history is gone then); applying the action again gives the same state, since
        // reading and completion are deterministic.
        if (!editor_ || editorRevision_ != shapeRevisions_[applied_])
            reposeNeutral();
        if (!editor_->redo())
            editor_->apply(poseActions_[poseApplied_]);
        ++poseApplied_;
    }
    revision_ = revisions_[done()];
    return true;
}

void Document::enablePosing(const pose::PoseModel& model, const std::filesystem::path& path, std::function<Mesh()> neutral)
{
    poseModel_ = &model;
    posesPath_ = absoluteNormal(path);
    neutral_ = std::move(neutral);
    editor_.reset();
}

void Document::buildEditor()
{
    if (!poseModel_)
        fail("posing needs a pose model (start the app with --poses POSES.model, `facesketch train-poses`)");
    Mesh neutral = neutral_();
    // As the saved face file holds it (PLY float32), so that a replay of the saved session
    // poses the very same numbers.
    neutral.V = neutral.V.cast<float>().cast<double>();
    pose::checkFace(*poseModel_, neutral, "the face to pose");
    editor_ = std::make_unique<pose::PoseEditor>(*poseModel_, neutral);
    editorRevision_ = shapeRevisions_[applied_];
}

void Document::preparePosing()
{
    if (!editor_ || editorRevision_ != shapeRevisions_[applied_])
        reposeNeutral();
}

void Document::addPoseAction(const sketch::PoseAction& action)
{
    preparePosing();
    sketch::PoseAction a = action;
    a.afterStrokes = static_cast<int>(applied_);
    editor_->apply(a);
    dropRedo();
    poseActions_.push_back(a);
    history_.push_back(Step::Pose);
    ++poseApplied_;
    revision_ = nextRevision_++;
    revisions_.push_back(revision_);
}

sketch::Session Document::session() const
{
    sketch::Session s;
    s.model = model_;
    s.dataset = dataset_;
    for (size_t i = 0; i < applied_; ++i)
        s.actions.push_back(strokes_[i].action);
    if (poseModel_)
        s.poses = posesPath_;
    s.tension = tension_;
    s.poseActions.assign(poseActions_.begin(), poseActions_.begin() + static_cast<long>(poseApplied_));
    return s;
}

void Document::save(const std::filesystem::path& path) const
{
    sketch::Session s = session();
    const std::filesystem::path folder = absoluteNormal(path).parent_path();
    s.model = relativeIfInside(model_, folder);
    s.dataset = relativeIfInside(dataset_, folder);
    if (!s.poses.empty())
        s.poses = relativeIfInside(posesPath_, folder);
    if (!s.poseActions.empty() && editor_) {
        // The face the pose actions pose, beside the session: `facesketch pose` and `animate`
        // read it from the session's `face`. Written first, so that a session never names a
        // face file that does not exist.
        const std::filesystem::path face = path.parent_path() / (path.stem().string() + ".face.ply");
        writeMesh(face, editor_->neutral());
        s.face = face.filename();
    }
    sketch::saveSession(path, s);
}

int Document::open(const std::filesystem::path& path)
{
    return load(sketch::loadSession(path), path, path.string());
}

int Document::load(const sketch::Session& session, const std::filesystem::path& sessionFile, const std::string& where)
{
    const auto [model, dataset] = sketch::sessionInputs(session, sessionFile);
    if (!samePath(model, model_))
        fail(where, ": model: drawn against ", model.string(), ", but the app has ", model_.string(), " open (start `facesketch gui ",
            where, "` to open it with its own model)");
    if (!samePath(dataset, dataset_))
        fail(where, ": dataset: drawn against ", dataset.string(), ", but the app has ", dataset_.string(), " open");
    // Back to no stroke, then the session's strokes; on an error, the document before is
    // restored (its strokes replayed: reading is deterministic, so the face is the same).
    if (!session.poseActions.empty() && !poseModel_)
        fail(where, ": ", session.poseActions.size(), " pose actions, but the app has no pose model (start it with --poses POSES.model)");
    Snapshot previous = capture();
    while (replayer_.undo()) { }
    std::vector<DocumentStroke> loaded;
    // keptBefore[k]: how many of the first k strokes of the file were applied (the rest were
    // dropped), so each pose action keeps its place among the strokes that remain.
    std::vector<int> keptBefore { 0 };
    std::vector<sketch::PoseAction> poses = session.poseActions;
    int dropped = 0;
    try {
        for (const sketch::StrokeAction& a : session.actions) {
            sketch::ReplayOutcome out = replayer_.apply(a);
            if (out.kind == sketch::ReplayOutcome::Kind::Applied)
                loaded.push_back({ a, std::move(out.reading) });
            else
                ++dropped;
            keptBefore.push_back(static_cast<int>(loaded.size()));
        }
        // Fresh revisions for the new neutrals, so that the editor is built for the last one.
        shapeRevisions_.clear();
        for (size_t i = 0; i <= loaded.size(); ++i)
            shapeRevisions_.push_back(nextRevision_++);
        if (!poses.empty()) {
            applied_ = loaded.size();
            buildEditor();
            for (size_t i = 0; i < poses.size(); ++i) {
                const size_t after = std::min(static_cast<size_t>(std::max(poses[i].afterStrokes, 0)), session.actions.size());
                poses[i].afterStrokes = keptBefore[after];
                try {
                    editor_->apply(poses[i]);
                } catch (const Error& e) {
                    fail(where, ": pose action ", i, ": ", e.what());
                }
            }
        }
    } catch (...) {
        restore(std::move(previous)); // with its undone actions, which redo as before
        throw;
    }
    // Opening replaces the document: the loaded strokes and pose actions become its history, in
    // the file's order. Over work, the document before is kept for undo and the loaded actions
    // are the base undo stops at; into an empty document they undo one by one.
    const bool overWork = !previous.history.empty() || !before_.empty();
    if (overWork)
        before_.push_back(std::move(previous));
    reopen_.clear();
    strokes_ = std::move(loaded);
    applied_ = strokes_.size();
    poseActions_ = std::move(poses);
    poseApplied_ = poseActions_.size();
    tension_ = session.tension;
    history_.clear();
    for (size_t i = 0, next = 0; i <= applied_; ++i) {
        for (; next < poseApplied_ && static_cast<size_t>(poseActions_[next].afterStrokes) == i; ++next)
            history_.push_back(Step::Pose);
        if (i < applied_)
            history_.push_back(Step::Shape);
    }
    revisions_.assign(1, nextRevision_++);
    for (size_t i = 0; i < history_.size(); ++i)
        revisions_.push_back(nextRevision_++);
    revision_ = revisions_.back();
    openBase_ = overWork ? history_.size() : 0;
    return dropped;
}

void Document::exportMesh(const std::filesystem::path& path) const
{
    const std::string ext = path.extension().string();
    if (ext != ".obj" && ext != ".ply")
        fail(path.string(), ": export writes .obj or .ply, not '", ext, "'");
    if (poseApplied_ > 0 && editor_)
        writeMesh(path, editor_->face());
    else
        writeMesh(path, face());
}

std::filesystem::path recoveryFile()
{
    const char* state = std::getenv("FACESKETCH_STATE_DIR");
    std::filesystem::path folder;
    if (state && *state) {
        folder = state;
    } else if (const char* xdg = std::getenv("XDG_STATE_HOME"); xdg && *xdg) {
        folder = std::filesystem::path(xdg) / "facesketch";
    } else if (const char* home = std::getenv("HOME"); home && *home) {
        folder = std::filesystem::path(home) / ".local" / "state" / "facesketch";
    } else {
        folder = std::filesystem::temp_directory_path() / "facesketch";
    }
    return folder / "recovery-session.json";
}

Autosave::Autosave(std::filesystem::path file, double intervalSeconds, std::uint64_t startRevision)
    : file_(std::move(file))
    , interval_(intervalSeconds)
    , savedRevision_(startRevision)
{
    if (!(intervalSeconds > 0))
        fail("autosave: the interval must be positive, got ", intervalSeconds, " s");
}

bool Autosave::tick(const Document& document, double nowSeconds)
{
    if (!last_) {
        last_ = nowSeconds;
        return false;
    }
    if (nowSeconds - *last_ < interval_ || document.revision() == savedRevision_)
        return false;
    last_ = nowSeconds;
    return save(document);
}

bool Autosave::flush(const Document& document)
{
    if (document.revision() == savedRevision_)
        return false;
    return save(document);
}

bool Autosave::save(const Document& document)
{
    if (file_.empty())
        return false;
    try {
        std::filesystem::create_directories(file_.parent_path());
        document.save(file_);
        savedRevision_ = document.revision();
        error_.clear();
        ++saves_;
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

} // namespace facesketch::gui

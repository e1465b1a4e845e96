#include "gui/document.h"

#include "core/error.h"
#include "io/mesh_io.h"

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

sketch::ReplayOutcome Document::addStroke(const sketch::StrokeAction& action)
{
    if (poseApplied_ > 0)
        fail("the face is posed (", poseApplied_, " pose actions in effect): undo them to sketch its shape");
    sketch::ReplayOutcome out = replayer_.apply(action);
    if (out.kind != sketch::ReplayOutcome::Kind::Applied)
        return out;
    strokes_.resize(applied_);
    poseActions_.clear(); // undone pose actions posed another neutral
    revisions_.resize(applied_ + 1);
    strokes_.push_back({ action, out.reading });
    ++applied_;
    revision_ = nextRevision_++;
    revisions_.push_back(revision_);
    return out;
}

bool Document::undo()
{
    if (poseApplied_ > 0) {
        if (!editor_ || !editor_->undo())
            return false;
        --poseApplied_;
    } else {
        if (applied_ == 0 || !replayer_.undo())
            return false;
        --applied_;
    }
    revision_ = revisions_[applied_ + poseApplied_];
    return true;
}

bool Document::redo()
{
    if (applied_ < strokes_.size()) {
        if (!replayer_.redo())
            return false;
        ++applied_;
    } else if (poseApplied_ < poseActions_.size()) {
        // The editor may have been rebuilt for this neutral since the action was undone (its
        // redo history is gone then); applying the action again gives the same state, since
        // reading and completion are deterministic.
        if (!editor_ || editorRevision_ != revisions_[applied_])
            buildEditor();
        if (!editor_->redo())
            editor_->apply(poseActions_[poseApplied_]);
        ++poseApplied_;
    } else {
        return false;
    }
    revision_ = revisions_[applied_ + poseApplied_];
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
    editorRevision_ = revisions_[applied_];
}

void Document::preparePosing()
{
    if (!editor_ || (poseApplied_ == 0 && editorRevision_ != revisions_[applied_]))
        buildEditor();
}

void Document::addPoseAction(const sketch::PoseAction& action)
{
    preparePosing();
    sketch::PoseAction a = action;
    a.afterStrokes = static_cast<int>(applied_);
    editor_->apply(a);
    strokes_.resize(applied_);
    poseActions_.resize(poseApplied_);
    revisions_.resize(applied_ + poseApplied_ + 1);
    poseActions_.push_back(a);
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
    // Back to no stroke, then the session's strokes; on an error, the strokes that were in
    // effect are replayed again (reading is deterministic, so the face is the same).
    if (!session.poseActions.empty() && !poseModel_)
        fail(where, ": ", session.poseActions.size(), " pose actions, but the app has no pose model (start it with --poses POSES.model)");
    const std::vector<DocumentStroke> before(strokes_.begin(), strokes_.begin() + static_cast<long>(applied_));
    std::unique_ptr<pose::PoseEditor> editorBefore = std::move(editor_);
    const std::uint64_t editorRevisionBefore = editorRevision_;
    const std::vector<std::uint64_t> revisionsBefore = revisions_;
    while (replayer_.undo()) { }
    std::vector<DocumentStroke> loaded;
    int dropped = 0;
    try {
        for (const sketch::StrokeAction& a : session.actions) {
            sketch::ReplayOutcome out = replayer_.apply(a);
            if (out.kind == sketch::ReplayOutcome::Kind::Applied)
                loaded.push_back({ a, std::move(out.reading) });
            else
                ++dropped;
        }
        if (!session.poseActions.empty()) {
            // A fresh revision for the new neutral, so that the editor is built for it.
            revisions_.assign(loaded.size() + 1, nextRevision_++);
            applied_ = loaded.size();
            buildEditor();
            for (size_t i = 0; i < session.poseActions.size(); ++i) {
                try {
                    editor_->apply(session.poseActions[i]);
                } catch (const Error& e) {
                    fail(where, ": pose action ", i, ": ", e.what());
                }
            }
        }
    } catch (...) {
        while (replayer_.undo()) { }
        for (const DocumentStroke& s : before)
            replayer_.apply(s.action);
        strokes_ = before;
        applied_ = before.size();
        editor_ = std::move(editorBefore);
        editorRevision_ = editorRevisionBefore;
        revisions_ = revisionsBefore;
        throw;
    }
    // Opening is one action: undo returns to the state before it is not offered (the tracking
    // history restarts), so the strokes are simply replaced.
    strokes_ = std::move(loaded);
    applied_ = strokes_.size();
    poseActions_ = session.poseActions;
    poseApplied_ = poseActions_.size();
    tension_ = session.tension;
    if (poseActions_.empty()) {
        revisions_.assign(1, nextRevision_++);
        for (size_t i = 0; i < applied_; ++i)
            revisions_.push_back(nextRevision_++);
    } else {
        // revisions_[applied_] is the editor's neutral, set above.
        for (size_t i = 0; i < applied_; ++i)
            revisions_[i] = nextRevision_++;
        for (size_t i = 0; i < poseApplied_; ++i)
            revisions_.push_back(nextRevision_++);
    }
    revision_ = revisions_.back();
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

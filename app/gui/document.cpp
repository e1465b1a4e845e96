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
    sketch::ReplayOutcome out = replayer_.apply(action);
    if (out.kind != sketch::ReplayOutcome::Kind::Applied)
        return out;
    strokes_.resize(applied_);
    revisions_.resize(applied_ + 1);
    strokes_.push_back({ action, out.reading });
    ++applied_;
    revision_ = nextRevision_++;
    revisions_.push_back(revision_);
    return out;
}

bool Document::undo()
{
    if (applied_ == 0 || !replayer_.undo())
        return false;
    --applied_;
    revision_ = revisions_[applied_];
    return true;
}

bool Document::redo()
{
    if (applied_ >= strokes_.size() || !replayer_.redo())
        return false;
    ++applied_;
    revision_ = revisions_[applied_];
    return true;
}

sketch::Session Document::session() const
{
    sketch::Session s;
    s.model = model_;
    s.dataset = dataset_;
    for (size_t i = 0; i < applied_; ++i)
        s.actions.push_back(strokes_[i].action);
    return s;
}

void Document::save(const std::filesystem::path& path) const
{
    sketch::Session s = session();
    const std::filesystem::path folder = absoluteNormal(path).parent_path();
    s.model = relativeIfInside(model_, folder);
    s.dataset = relativeIfInside(dataset_, folder);
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
    const std::vector<DocumentStroke> before(strokes_.begin(), strokes_.begin() + static_cast<long>(applied_));
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
    } catch (...) {
        while (replayer_.undo()) { }
        for (const DocumentStroke& s : before)
            replayer_.apply(s.action);
        strokes_ = before;
        applied_ = before.size();
        throw;
    }
    // Opening is one action: undo returns to the state before it is not offered (the tracking
    // history restarts), so the strokes are simply replaced.
    strokes_ = std::move(loaded);
    applied_ = strokes_.size();
    revisions_.assign(1, nextRevision_++);
    for (size_t i = 0; i < applied_; ++i)
        revisions_.push_back(nextRevision_++);
    revision_ = revisions_.back();
    return dropped;
}

void Document::exportMesh(const std::filesystem::path& path) const
{
    const std::string ext = path.extension().string();
    if (ext != ".obj" && ext != ".ply")
        fail(path.string(), ": export writes .obj or .ply, not '", ext, "'");
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

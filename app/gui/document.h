#pragma once
// The app's document: the session being drawn (sketch/session.h, the file `facesketch sketch`
// replays) and the face it gives. Strokes go through sketch::SessionReplayer, the code path the
// CLI replays sessions with, so a saved session replays to the identical face. Only strokes
// that pin something enter the session (the CLI skips the others, so the faces agree).
//
// Every stroke and pose action can be undone and redone; undo and redo restore the tracking
// model's stored state, so the face after undo is bit-identical to the face before the undone
// action. Opening a session over work (a document with any history, or itself opened over work)
// is one action: undo right after it brings back the document as it was before the open, with
// its own undo and redo history, and redo opens the session again; the opened session's own
// actions are its content then, not undone one by one. Opened into an empty document (nothing to
// bring back, e.g. the app started with a session), its actions undo one by one in the file's
// order. Undoing or redoing an open replays the other document's strokes (tens of ms a stroke).
//
// Posing (issue 13, thesis 5.3-5.5). With a pose model (enablePosing), pose actions (pose strokes,
// keyframes, clears) go through pose::PoseEditor, the code path of `facesketch pose` and
// `animate`. They pose the head that all the shape strokes in effect build (the neutral), as
// `facesketch pose --session` replays a session. Shape strokes and pose actions interleave in one
// history: a shape stroke drawn while the face is posed reshapes the neutral, and the pose
// actions in effect are replayed on the new neutral (reading and completion are deterministic);
// undoing it does the same for the old neutral. The neutral is rounded to float32, as the face
// file a saved session names holds it (io/mesh_io.h PLY), so `facesketch pose --session` replays
// the saved session to the app's posed face bit for bit.

#include "pose/pose_session.h"
#include "sketch/replay.h"
#include "sketch/session.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace facesketch::gui {

/// A stroke in the document: what the user drew and how it was read.
struct DocumentStroke {
    sketch::StrokeAction action;
    sketch::StrokeReading reading;
};

class Document {
public:
    /// `model` and `dataset` are the inputs the replayer was built from (made absolute here);
    /// they are written into saved sessions. The replayer must be fresh (no stroke applied) and
    /// outlive the document.
    Document(sketch::SessionReplayer& replayer, const std::filesystem::path& model, const std::filesystem::path& dataset);

    /// Reads and applies one stroke. Applied: it becomes the last action of the session, any
    /// undone actions are forgotten, and the pose actions in effect pose the new neutral.
    /// PinsNothing or Refused: nothing changes (the outcome says why). Throws Error as
    /// SessionReplayer::apply does (nothing changed), or naming the pose action the new neutral
    /// cannot replay (the stroke is taken back; undone actions are forgotten, as the replayer
    /// forgot them). Taken by value: `action` may be one of this document's own undone strokes
    /// (strokes()[i].action), which forgetting the undone actions destroys.
    sketch::ReplayOutcome addStroke(sketch::StrokeAction action);

    /// Undoes the last action in effect (or the open that replaced earlier work, see above);
    /// false (nothing changed) if there is none.
    bool undo();
    /// Redoes the first undone action (or an undone open); false if there is none.
    bool redo();
    bool canUndo() const { return done() > openBase_ || undoReopens(); }
    bool canRedo() const { return done() < history_.size() || !reopen_.empty(); }
    /// Whether undo() would go back to the document before an open (and redo() open it again).
    bool undoReopens() const { return !before_.empty() && done() == openBase_; }
    bool redoReopens() const { return done() == history_.size() && !reopen_.empty(); }

    /// Allows pose actions: `model` (kept by reference, keep it alive; `path` is written into
    /// saved sessions as `poses`) poses the mesh `neutral()` returns for the current shape face
    /// (the whole head, #V by 3 mm, the pose model's topology). `neutral` is called with the
    /// document already in the new shape state (face(), appliedCount()).
    void enablePosing(const pose::PoseModel& model, const std::filesystem::path& path, std::function<Mesh()> neutral);
    bool posingEnabled() const { return poseModel_ != nullptr; }
    /// Builds the pose editor for the current neutral if it has none yet. Throws Error if posing
    /// is not enabled or the neutral does not fit the pose model (another topology).
    void preparePosing();
    /// Applies a pose action (its afterStrokes is set here) and forgets any undone actions.
    /// Throws Error, nothing changed, if posing is not enabled or the editor refuses it (a stroke
    /// that hits no feature point cluster, a keyframe time already used).
    void addPoseAction(const sketch::PoseAction& action);
    /// Every pose action drawn, including undone ones after poseAppliedCount().
    const std::vector<sketch::PoseAction>& poseActions() const { return poseActions_; }
    size_t poseAppliedCount() const { return poseApplied_; }
    /// The pose editor (its face, reading, keyframes), or nullptr before the first pose action.
    const pose::PoseEditor* poseEditor() const { return editor_.get(); }
    const std::filesystem::path& posesPath() const { return posesPath_; }
    /// The timeline's tension (session `tension`, kept from an opened session).
    double tension() const { return tension_; }

    /// Every stroke drawn, including undone ones after appliedCount().
    const std::vector<DocumentStroke>& strokes() const { return strokes_; }
    /// How many of strokes() are in effect (the rest are undone, kept for redo).
    size_t appliedCount() const { return applied_; }

    /// The current face (#V by 3, mm, the model's topology).
    Mesh face() const { return replayer_.face(); }
    sketch::SessionReplayer& replayer() { return replayer_; }

    /// The session of the strokes and pose actions in effect, with absolute model, dataset and
    /// pose model paths (no face file: save() writes one).
    sketch::Session session() const;

    /// Writes the session atomically to `path`. The model and dataset paths are written relative
    /// to the file's folder when they lie inside it, absolute otherwise. With pose actions, the
    /// neutral they pose is written beside it as <stem>.face.ply and named as the session's
    /// `face`. Throws Error naming the file if it cannot be written.
    void save(const std::filesystem::path& path) const;

    /// Replaces the strokes and pose actions with those of the session file at `path`, replayed
    /// in order (strokes that pin nothing or are refused are dropped, as `facesketch sketch`
    /// skips them; the pose actions then pose the head of all its strokes, the session's own
    /// `face` file is not read). Throws Error naming the file, before anything changes, if it
    /// cannot be read, was drawn against another model or dataset, or has pose actions that the
    /// app cannot replay (no pose model, a stroke that hits nothing); returns how many strokes
    /// were dropped. Undoable as one action when it replaces work (see above); forgets an undone
    /// open.
    int open(const std::filesystem::path& path);
    /// open() from a session in memory; `where` names it in errors.
    int load(const sketch::Session& session, const std::filesystem::path& sessionFile, const std::string& where);

    /// Writes the current face as OBJ or PLY (by extension; atomic): the posed head when a pose
    /// action is in effect, else the shape face. Throws Error naming the file for another
    /// extension.
    void exportMesh(const std::filesystem::path& path) const;

    /// Changes with every change of the session (strokes in effect); for autosave and titles.
    std::uint64_t revision() const { return revision_; }
    /// The revision last saved or opened by the user (not by autosave).
    std::uint64_t savedRevision() const { return savedRevision_; }
    void markSaved() { savedRevision_ = revision_; }

    const std::filesystem::path& modelPath() const { return model_; }
    const std::filesystem::path& datasetPath() const { return dataset_; }

private:
    enum class Step { Shape, Pose };
    // One whole document: its history, what is in effect, its revisions and its pose editor.
    struct Snapshot {
        std::vector<DocumentStroke> strokes;
        size_t applied = 0;
        std::vector<sketch::PoseAction> poseActions;
        size_t poseApplied = 0;
        std::vector<Step> history;
        double tension = 0;
        std::vector<std::uint64_t> revisions, shapeRevisions;
        std::uint64_t revision = 0;
        size_t openBase = 0;
        std::unique_ptr<pose::PoseEditor> editor;
        std::uint64_t editorRevision = 0;
    };
    // The document as it is (its editor is moved into the snapshot).
    Snapshot capture();
    // Makes `s` the document: the replayer replays its strokes (and undoes its undone ones, so
    // that they redo), its editor is kept if it is of the restored neutral, else rebuilt.
    void restore(Snapshot&& s);
    size_t done() const { return applied_ + poseApplied_; }
    void buildEditor();
    // After the neutral changed (a shape stroke applied or undone while posed): a new editor for
    // it with the pose actions in effect applied again.
    void reposeNeutral();
    // Forgets the undone actions (a new action was taken).
    void dropRedo();

    sketch::SessionReplayer& replayer_;
    std::filesystem::path model_, dataset_;
    std::vector<DocumentStroke> strokes_;
    size_t applied_ = 0;
    const pose::PoseModel* poseModel_ = nullptr;
    std::filesystem::path posesPath_;
    std::function<Mesh()> neutral_;
    std::unique_ptr<pose::PoseEditor> editor_;
    // The shape revision the editor's neutral was built for.
    std::uint64_t editorRevision_ = 0;
    std::vector<sketch::PoseAction> poseActions_;
    size_t poseApplied_ = 0;
    // The order of strokes_ and poseActions_ in the one history; the first done() are in
    // effect (undone actions are always its tail, so each list's undone part is its own tail).
    std::vector<Step> history_;
    double tension_ = 0;
    std::uint64_t revision_ = 0;
    std::uint64_t savedRevision_ = 0;
    // Revisions of the states after 0..history_.size() actions (index done()), so undoing back
    // to a saved state is clean; and of the neutrals after 0..strokes_.size() shape strokes (the
    // editor is rebuilt when its neutral's revision is not the current one).
    std::vector<std::uint64_t> revisions_ { 0 };
    std::vector<std::uint64_t> shapeRevisions_ { 0 };
    std::uint64_t nextRevision_ = 1;
    // Opens over work: the documents they replaced (last: the latest), the opened documents
    // undone (for redo), and how many steps of history_ came with the open (undo stops there
    // and undoes the open instead; 0 with nothing before).
    std::vector<Snapshot> before_;
    std::vector<Snapshot> reopen_;
    size_t openBase_ = 0;
};

/// Where the app autosaves: $FACESKETCH_STATE_DIR, else $XDG_STATE_HOME/facesketch, else
/// $HOME/.local/state/facesketch, then "recovery-session.json".
std::filesystem::path recoveryFile();

/// Autosave of a document every `intervalSeconds` (when it changed since the last autosave)
/// and on exit, to a session file the next start offers to restore.
class Autosave {
public:
    /// Nothing is saved until the document's revision differs from `startRevision` (an
    /// untouched document never overwrites the recovery of an earlier run). An empty `file`
    /// turns autosaving off: tick and flush never write (a benchmark's scripted strokes must not
    /// replace the user's recovery file).
    Autosave(std::filesystem::path file, double intervalSeconds, std::uint64_t startRevision);
    /// Saves if at least the interval has passed since the last autosave (or the start) and
    /// the document's revision differs from the one last autosaved. `nowSeconds` is any
    /// monotonic clock. Returns whether it saved. An error is kept in lastError(), not thrown:
    /// a failing autosave must never stop the user's work.
    bool tick(const Document& document, double nowSeconds);
    /// Saves now if the document changed since the last autosave (on exit).
    bool flush(const Document& document);
    const std::filesystem::path& file() const { return file_; }
    const std::string& lastError() const { return error_; }
    int saves() const { return saves_; }

private:
    bool save(const Document& document);
    std::filesystem::path file_;
    double interval_;
    std::optional<double> last_;
    std::uint64_t savedRevision_;
    std::string error_;
    int saves_ = 0;
};

} // namespace facesketch::gui

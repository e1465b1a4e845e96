// `facesketch gui [SESSION | MODEL DATASET]`: the interactive app (issue 14). A window with
// the face, its contours and the strokes drawn on it; strokes are read with the left button and
// applied through the same SessionReplayer as `facesketch sketch`; navigation as in Blender
// (gui/navigation.h); panels for the reading options, the similar training faces, files and
// data. Long work (synthesising and training the built-in data, loading a dataset, the curvature
// pass) runs on a worker thread (gui/worker.h) with a progress bar and Cancel.
//
// Pose mode (Tab; thesis 5.3-5.5, engine/pose): left-button strokes are pose strokes, read for
// feature points and completed to a pose by gui::Document's pose::PoseEditor; the completed
// feature points and the ones the strokes identified are drawn as points. The timeline panel
// adds keyframes from the current pose at the current time, moves and deletes them (session
// actions like the rest, so undoable), scrubs, plays (at a frame rate,
// looping or not) through pose::TimelinePlayer, each frame rebuilt by the mapping, and exports
// the played timeline as glTF (pose/animation.h), as `facesketch animate` does.

#include "commands.h"
#include "sketch_data.h"

#include "contours/contour_lines.h"
#include "contours/curvature.h"
#include "contours/curvature_cache.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "dataset/synth/synth_dataset.h"
#include "geometry/normals.h"
#include "gui/document.h"
#include "gui/navigation.h"
#include "gui/overlay.h"
#include "gui/window.h"
#include "gui/worker.h"
#include "model/head_assembly.h"
#include "model/head_model.h"
#include "pose/animation.h"
#include "pose/minimal_poses.h"
#include "pose/pose_file.h"
#include "render/scene_renderer.h"
#include "sketch/feedback.h"
#include "sketch/simulate.h"
#include "stats/model_file.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <sstream>

namespace facesketch::app {

namespace {

namespace fs = std::filesystem;

struct GuiCommand {
    std::vector<std::string> inputs;
    std::string sessionOut, exportOut, screenshot, poses, glbOut;
    std::string mode = "sketch";
    double time = -1;
    bool play = false;
    int quitAfterFrames = 0;
    int benchFrames = 0;
    int width = 1280, height = 800;
    int samples = 4;
    double motionScale = 0.5; ///< the scene's resolution while the view moves (1: always full)
    gui::Present present = gui::Present::Auto;
    double autosaveSeconds = 30;
    bool restore = false;
    bool printGuides = false;
    bool overlay = false;
    std::string view = "front";
};

// Everything loaded for one model and dataset (on the worker thread, then handed over).
struct Loaded {
    fs::path model, dataset;
    std::unique_ptr<stats::FaceModel> faceModel;
    std::unique_ptr<SketchData> data;
    std::unique_ptr<gpu::ScopedDevice> compute; ///< the reader's and the overlay's device (not the window's)
    std::unique_ptr<sketch::SessionReplayer> replayer;
    std::unique_ptr<gui::CandidateCloud> cloud;
    fs::path posesPath;                         ///< empty: no posing
    std::unique_ptr<pose::PoseModel> poseModel; ///< loaded from posesPath
    ~Loaded()
    {
        // The GPU objects before their device.
        cloud.reset();
        replayer.reset();
        compute.reset();
    }
};

fs::path builtInFolder()
{
    const fs::path cache = defaultCacheFolder();
    if (cache.empty())
        fail("gui: no cache folder for the built-in data: set FACESKETCH_CACHE_DIR, XDG_CACHE_HOME or HOME");
    return cache / "builtin-high-v23";
}

// The built-in data: the synthetic high-resolution set and its model, made once into the cache.
void makeBuiltIn(const fs::path& folder, gui::Progress& progress)
{
    const fs::path faces = folder / "faces", model = folder / "faces.model";
    fs::create_directories(folder);
    if (!fs::exists(faces / "manifest.json")) {
        dataset::SynthOptions synth;
        synth.resolution = dataset::Resolution::High;
        dataset::writeSynthDataset(faces, synth,
            [&](int done, int total) { progress.report(0.4 * done / std::max(total, 1), "synthesising the built-in faces"); });
    }
    if (!fs::exists(model)) {
        const dataset::Dataset ds = dataset::openDataset(faces);
        const stats::FaceModel m = model::trainHeadModel(
            ds, {}, [&](const std::string& what, double f) { progress.report(0.4 + 0.4 * f, "training: " + what); });
        stats::saveFaceModel(m, model);
    }
}

// The built-in pose model: a posed synthetic set of the built-in faces' resolution (its
// topology), trained once into the cache beside the built-in face model.
void makeBuiltInPoses(const fs::path& folder, gui::Progress& progress)
{
    const fs::path posed = folder / "posed", model = folder / "faces.poses";
    if (fs::exists(model))
        return;
    if (!fs::exists(posed / "manifest.json")) {
        dataset::SynthOptions synth;
        synth.resolution = dataset::Resolution::High;
        synth.identities = 24;
        synth.poses = true;
        synth.seed = 7;
        dataset::writeSynthDataset(posed, synth,
            [&](int done, int total) { progress.report(0.6 * done / std::max(total, 1), "synthesising the built-in poses"); });
    }
    progress.report(0.6, "training the built-in pose model");
    const dataset::Dataset ds = dataset::openDataset(posed);
    const pose::PoseSet all = pose::loadPoseSet(ds, { dataset::Role::Train, dataset::Role::Contour });
    const pose::PoseSet train = pose::selectRole(all, dataset::Role::Train);
    const pose::PoseSet contour = pose::selectRole(all, dataset::Role::Contour);
    progress.checkCancelled();
    const pose::PoseModel m = pose::trainPoseModel(train, contour.identityCount() > 0 ? contour : train, pose::loadMinimalPoses(), {});
    pose::savePoseModel(m, model);
}

std::unique_ptr<Loaded> load(const fs::path& model, const fs::path& dataset, const fs::path& poses, gui::Progress& progress)
{
    auto l = std::make_unique<Loaded>();
    l->posesPath = poses;
    l->model = model;
    l->dataset = dataset;
    progress.report(0.8, "loading the model");
    l->faceModel = std::make_unique<stats::FaceModel>(stats::loadFaceModel(model));
    progress.report(0.82, "loading the dataset");
    l->data = std::make_unique<SketchData>(loadSketchData(dataset.string(), l->faceModel.get()));
    progress.report(0.86, "curvature of the candidate faces");
    l->compute = std::make_unique<gpu::ScopedDevice>();
    l->replayer = std::make_unique<sketch::SessionReplayer>(
        **l->compute, *l->faceModel, l->data->candidateFaces, l->data->flags, l->data->landmarks, model.string());
    progress.report(0.94, "candidate cloud for the overlay");
    l->cloud = std::make_unique<gui::CandidateCloud>(**l->compute, l->data->candidateFaces, l->data->flags, defaultCacheFolder());
    if (!poses.empty()) {
        progress.report(0.98, "loading the pose model");
        l->poseModel = std::make_unique<pose::PoseModel>(pose::loadPoseModel(poses));
    }
    progress.report(1.0, "ready");
    return l;
}

double percentile(std::vector<double> v, double p)
{
    if (v.empty())
        return 0;
    std::sort(v.begin(), v.end());
    const size_t i = std::min(v.size() - 1, static_cast<size_t>(std::ceil(p * static_cast<double>(v.size()))) - (p > 0 ? 1 : 0));
    return v[i];
}

glm::vec3 toVec3(const Eigen::Vector3d& p)
{
    return { static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()) };
}

glm::dvec3 viewDirection(const OrbitView& v)
{
    const double az = glm::radians(v.angles.azimuthDeg), el = glm::radians(v.angles.elevationDeg);
    return { std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el) };
}

class App {
public:
    explicit App(const GuiCommand& c);
    ~App();
    void run();

private:
    // Data and document.
    void startLoad(fs::path model, fs::path dataset, fs::path poses, bool builtIn);
    void startTrain(fs::path dataset, fs::path model);
    void install(std::unique_ptr<Loaded> loaded);
    void pollJob();
    // Input.
    void onMouseButton(int button, int action, int mods, double x, double y);
    void onCursor(double x, double y);
    void onScroll(double steps);
    void onKey(int key, int action, int mods);
    void applyStroke(const sketch::Stroke& stroke);
    // Posing.
    void setPoseMode(bool on);
    void applyPoseStroke(const sketch::Stroke& stroke);
    void addPoseAction(const sketch::PoseAction& action, const std::string& what);
    void addKeyframe();
    /// Moves the selected keyframe to the current time, or deletes it (session version 3
    /// actions, so both replay and undo like every other action).
    void moveKeyframe();
    void deleteKeyframe();
    void switchInterpretation();
    void setTime(double seconds);
    void togglePlay();
    void advancePlayback(double now);
    void poseChanged();
    void showFrame();
    void exportAnimation(const fs::path& path);
    void undo();
    void redo();
    void save(const fs::path& path);
    void open(const fs::path& path);
    void exportFace(const fs::path& path);
    // Scene.
    void faceChanged();
    void viewChanged();
    void updateStrokeItems();
    void updateOverlay();
    void printGuides();
    Mesh shapeHead() const;
    Mesh displayMesh() const;
    Mesh contourFace() const;
    bool showingTimeline() const;
    // Panels.
    void panels();
    void timelinePanel();
    void say(const std::string& text);

    GuiCommand c_;
    gui::Window window_;
    std::unique_ptr<SceneRenderer> scene_;
    std::unique_ptr<gui::Job> job_;
    std::unique_ptr<Loaded> pending_;
    std::unique_ptr<Loaded> loaded_;
    std::unique_ptr<gui::Document> doc_;
    std::unique_ptr<gui::Autosave> autosave_;
    std::unique_ptr<gui::Navigator> nav_;
    gui::Pointer pointer_;
    std::optional<sketch::Stroke> released_;
    double releasedAt_ = 0;
    bool quit_ = false;

    // Scene items.
    DrawId faceItem_ = 0, contourItem_ = 0, drawingItem_ = 0, flashItem_ = 0;
    std::vector<DrawId> strokeItems_, interpretedItems_;
    DrawId fpItem_ = 0, hitItem_ = 0;
    bool haveItems_ = false;
    Curvature curvature_;
    ContourParams contourParams_;
    OrbitView lastView_ {};
    bool viewDirty_ = true;
    double flashUntil_ = 0;
    int overlayQuietFrames_ = 0;
    bool overlayStale_ = true;

    // Panel state.
    int mapper_ = 2; // hmm
    int surface_ = 0;
    bool correlation_ = true, symmetry_ = false;
    bool showContours_ = true, showOverlay_ = false, showStrokes_ = true;
    std::string status_;
    std::vector<std::pair<std::string, double>> similar_;
    char sessionPath_[512] = "session.json";
    char exportPath_[512] = "face.ply";
    char modelPath_[512] = "";
    char datasetPath_[512] = "";
    std::optional<sketch::Session> recovery_;
    fs::path sessionArg_;
    std::uint64_t readyFrames_ = 0;
    bool inputSeen_ = false;             ///< an input event arrived since the last frame
    int idleFrames_ = 0;                 ///< frames in a row in which nothing changed
    std::optional<OrbitView> drawnView_; ///< the view of the last frame drawn
    bool reducedShown_ = false;          ///< the last frame drew the scene at motionScale
    std::uint32_t reducedTarget_ = 0;    ///< scene_'s target for reduced frames (one sample)

    // Pose mode and the timeline.
    bool poseMode_ = false;
    bool alternative_ = false;
    double time_ = 0; ///< the timeline's current time, s
    /// The keyframe the timeline panel's buttons act on (its time), NaN for none.
    double selectedKey_ = std::numeric_limits<double>::quiet_NaN();
    double fps_ = 30; ///< playback and glTF export frame rate
    bool playing_ = false, loop_ = true;
    double lastTick_ = -1;
    bool timelineShown_ = false;               ///< the face shows the timeline at time_ (else the current pose)
    std::unique_ptr<pose::Timeline> timeline_; ///< through the keyframes in effect (two or more)
    std::unique_ptr<pose::TimelinePlayer> player_;
    Vertices frame_; ///< the timeline's face at the shown time
    double frameTime_ = -1;
    bool contoursStale_ = false; ///< hidden during playback, to be rebuilt when it stops
    char glbPath_[512] = "timeline.glb";
    bool trace_ = std::getenv("FACESKETCH_GUI_TRACE") != nullptr; ///< print input events and frame times
};

App::App(const GuiCommand& c)
    : c_(c)
    , window_({ c.width, c.height, "FaceSketch", c.samples, c.present })
{
    std::cout << "gui: presenting through " << window_.presentPath() << std::endl;
    RenderTargetFormat target;
    target.color = window_.colorFormat();
    target.samples = window_.samples();
    target.renderPass = window_.renderPass();
    scene_ = std::make_unique<SceneRenderer>(window_.device(), target, gpu::framesInFlight);
    RenderTargetFormat reduced = target;
    reduced.samples = 1;
    reduced.renderPass = window_.reducedRenderPass();
    reducedTarget_ = scene_->addTarget(reduced);
    if (!c.sessionOut.empty())
        std::snprintf(sessionPath_, sizeof sessionPath_, "%s", c.sessionOut.c_str());
    if (!c.exportOut.empty())
        std::snprintf(exportPath_, sizeof exportPath_, "%s", c.exportOut.c_str());
    if (!c.glbOut.empty())
        std::snprintf(glbPath_, sizeof glbPath_, "%s", c.glbOut.c_str());
    if (c.mode != "sketch" && c.mode != "pose")
        fail("gui: --mode: 'sketch' or 'pose', not '", c.mode, "'");
    showOverlay_ = c.overlay;

    gui::WindowEvents events;
    events.mouseButton = [this](int b, int a, int m, double x, double y) { onMouseButton(b, a, m, x, y); };
    events.cursor = [this](double x, double y) { onCursor(x, y); };
    events.scroll = [this](double s) { onScroll(s); };
    events.key = [this](int k, int a, int m) { onKey(k, a, m); };
    window_.setEvents(std::move(events));

    // What to open: SESSION, MODEL DATASET, or the built-in data.
    if (c.inputs.size() == 1) {
        sessionArg_ = c.inputs[0];
        const sketch::Session s = sketch::loadSession(sessionArg_);
        const auto [model, dataset] = sketch::sessionInputs(s, sessionArg_);
        if (c.sessionOut.empty())
            std::snprintf(sessionPath_, sizeof sessionPath_, "%s", sessionArg_.string().c_str());
        // The session's own pose model unless --poses names another.
        const fs::path poses = !c.poses.empty() ? fs::path(c.poses)
            : s.poses.empty()                   ? fs::path()
                                                : sketch::sessionPath(sessionArg_, s.poses);
        startLoad(model, dataset, poses, false);
    } else if (c.inputs.size() == 2) {
        startLoad(c.inputs[0], c.inputs[1], c.poses, false);
    } else if (c.inputs.empty()) {
        const fs::path folder = builtInFolder();
        startLoad(folder / "faces.model", folder / "faces", c.poses.empty() ? folder / "faces.poses" : fs::path(c.poses), true);
    } else {
        fail("gui: give SESSION, or MODEL DATASET, or nothing (the built-in data); got ", c.inputs.size(), " arguments");
    }
}

App::~App()
{
    // The job writes pending_ and the frames in flight read the scene: both end first.
    job_.reset();
    window_.waitIdle();
}

void App::startLoad(fs::path model, fs::path dataset, fs::path poses, bool builtIn)
{
    if (job_ && !job_->finished())
        return;
    std::snprintf(modelPath_, sizeof modelPath_, "%s", model.string().c_str());
    std::snprintf(datasetPath_, sizeof datasetPath_, "%s", dataset.string().c_str());
    job_ = std::make_unique<gui::Job>(builtIn ? "preparing the built-in data" : "loading " + dataset.filename().string(),
        [this, model, dataset, poses, builtIn](gui::Progress& p) {
            if (builtIn) {
                makeBuiltIn(model.parent_path(), p);
                if (poses == model.parent_path() / "faces.poses")
                    makeBuiltInPoses(model.parent_path(), p);
            }
            pending_ = load(model, dataset, poses, p);
        });
}

void App::startTrain(fs::path dataset, fs::path model)
{
    if (job_ && !job_->finished())
        return;
    const fs::path poses = loaded_ ? loaded_->posesPath : fs::path();
    job_
        = std::make_unique<gui::Job>("training a model on " + dataset.filename().string(), [this, model, dataset, poses](gui::Progress& p) {
              const dataset::Dataset ds = dataset::openDataset(dataset);
              const stats::FaceModel m
                  = model::trainHeadModel(ds, {}, [&](const std::string& what, double f) { p.report(0.8 * f, "training: " + what); });
              stats::saveFaceModel(m, model);
              pending_ = load(model, dataset, poses, p);
          });
}

void App::pollJob()
{
    if (!job_ || !job_->finished())
        return;
    const gui::Job::State state = job_->state();
    const std::string name = job_->name(), error = job_->error();
    job_.reset(); // joins; pending_ is ours now
    if (state == gui::Job::State::Done) {
        install(std::move(pending_));
    } else if (state == gui::Job::State::Cancelled) {
        pending_.reset();
        say(name + ": cancelled");
        if (!loaded_)
            quit_ = true; // nothing to show without data
    } else {
        pending_.reset();
        say(name + ": " + error);
        std::cerr << "facesketch gui: " << name << ": " << error << "\n";
        if (!loaded_)
            throw Error(error);
    }
}

void App::install(std::unique_ptr<Loaded> loaded)
{
    if (doc_ && autosave_)
        autosave_->flush(*doc_);
    window_.waitIdle(); // the old items may be in flight
    scene_->clear();
    haveItems_ = false;
    // The player refers to the timeline and the old pose model: both go before the data.
    player_.reset();
    timeline_.reset();
    playing_ = false;
    timelineShown_ = false;
    doc_.reset();
    loaded_ = std::move(loaded);
    doc_ = std::make_unique<gui::Document>(*loaded_->replayer, loaded_->model, loaded_->dataset);
    if (loaded_->poseModel)
        doc_->enablePosing(*loaded_->poseModel, loaded_->posesPath, [this] { return shapeHead(); });
    // A benchmark neither offers nor writes the recovery file: its scripted stroke is not work.
    autosave_
        = std::make_unique<gui::Autosave>(c_.benchFrames > 0 ? fs::path() : gui::recoveryFile(), c_.autosaveSeconds, doc_->revision());

    const Mesh mean = meanMesh(*loaded_->faceModel);
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_.glfw(), &w, &h);
    OrbitView home = frameMeshView(mean, { 0, 0 }, std::max(w, 1), std::max(h, 1));
    nav_ = std::make_unique<gui::Navigator>(home);
    const ViewAngles a = parseView(c_.view);
    nav_->orbit(-a.azimuthDeg / 0.4, a.elevationDeg / 0.4);
    contourParams_.silhouetteThreshold = defaultSilhouetteThreshold(mean.V.rows());
    contourParams_.featureSize = meanEdgeLength(mean);

    faceItem_ = scene_->addMesh(displayMesh());
    contourItem_ = scene_->addLines({}, { { 0.08f, 0.08f, 0.1f, 1 } }, { 1.5f, true });
    drawingItem_ = scene_->addScreenPolyline({}, { { 0.85f, 0.1f, 0.1f, 1 } }, 2.0f);
    flashItem_ = scene_->addPoints({}, { { 0.1f, 0.8f, 0.2f, 1 } }, 6.0f);
    fpItem_ = scene_->addPoints({}, { { 0.15f, 0.35f, 0.95f, 1 } }, 7.0f);
    hitItem_ = scene_->addPoints({}, { { 0.95f, 0.45f, 0.05f, 1 } }, 10.0f);
    haveItems_ = true;

    if (!sessionArg_.empty()) {
        open(sessionArg_);
        sessionArg_.clear();
    } else if (fs::exists(autosave_->file())) {
        try {
            sketch::Session s = sketch::loadSession(autosave_->file());
            const auto [model, dataset] = sketch::sessionInputs(s, autosave_->file());
            const bool any = !s.actions.empty() || !s.poseActions.empty();
            if (any && fs::equivalent(model, loaded_->model) && fs::equivalent(dataset, loaded_->dataset))
                recovery_ = std::move(s);
            else if (any)
                say("a recovery session for other data is at " + autosave_->file().string());
        } catch (const std::exception& e) {
            say(std::string("the recovery file is unusable: ") + e.what());
        }
        if (recovery_ && c_.restore) {
            const size_t n = recovery_->actions.size();
            doc_->load(*recovery_, autosave_->file(), autosave_->file().string());
            recovery_.reset();
            say("restored " + std::to_string(n) + " strokes from " + autosave_->file().string());
            std::cout << "gui: restored " << doc_->appliedCount() << " strokes from the recovery file" << std::endl;
            if (doc_->poseAppliedCount() > 0)
                std::cout << "gui: restored " << doc_->poseAppliedCount() << " pose actions from the recovery file" << std::endl;
        }
    }
    if (!doc_->posingEnabled())
        poseMode_ = false; // new data without a pose model
    if (c_.mode == "pose")
        setPoseMode(true);
    if (poseMode_ && c_.time >= 0) {
        poseChanged();
        setTime(c_.time);
    }
    if (poseMode_ && c_.play) {
        poseChanged();
        playing_ = timeline_ != nullptr;
    }
    faceChanged();
    viewDirty_ = true;
    // One path a line, so that a script can take the built-in data's folder from here.
    std::cout << "gui: model " << loaded_->model.string() << "\ngui: dataset " << loaded_->dataset.string() << std::endl;
    std::cout << "gui: ready, " << loaded_->faceModel->vertexCount() << " vertices, recovery file "
              << (autosave_->file().empty() ? std::string("none (a benchmark)") : autosave_->file().string()) << std::endl;
}

void App::say(const std::string& text)
{
    status_ = text;
}

bool App::showingTimeline() const
{
    return poseMode_ && timelineShown_ && player_ && frame_.rows() > 0;
}

Mesh App::displayMesh() const
{
    // In pose mode: the timeline's frame, or the current pose once a pose action is in effect.
    if (poseMode_ && doc_->poseEditor()) {
        Mesh mesh = doc_->poseEditor()->face();
        if (showingTimeline())
            mesh.V = frame_;
        else if (doc_->poseAppliedCount() == 0)
            return shapeHead();
        return mesh;
    }
    return shapeHead();
}

Mesh App::contourFace() const
{
    const stats::FaceModel& m = *loaded_->faceModel;
    if (!(poseMode_ && doc_->poseEditor() && (doc_->poseAppliedCount() > 0 || showingTimeline())))
        return doc_->face();
    // The skin of the posed head (model/head_assembly.h: skin vertex v is head vertex skinBegin + v).
    const Mesh head = displayMesh();
    const Eigen::Index skin = m.vertexCount();
    if (m.head.vertexCount == 0 || head.V.rows() < m.head.skinBegin + skin)
        return doc_->face();
    Mesh face;
    face.F = m.triangles;
    face.V = head.V.middleRows(m.head.skinBegin, skin);
    return face;
}

Mesh App::shapeHead() const
{
    const stats::FaceModel& m = *loaded_->faceModel;
    const Eigen::VectorXd& face = loaded_->replayer->tracking().face();
    // The rigid parts (eyes, teeth, tongue) follow the skin when the model knows the head.
    if (m.head.vertexCount > 0)
        return model::assembleHead(m.head, m.meanFace, face);
    Mesh mesh;
    mesh.F = m.triangles;
    mesh.V = asVertices(face);
    return mesh;
}

void App::onMouseButton(int button, int action, int mods, double x, double y)
{
    inputSeen_ = true;
    if (trace_)
        std::cout << "trace: button " << button << " action " << action << " at " << x << "," << y << std::endl;
    if (!doc_ || recovery_)
        return;
    const gui::Pointer::Button b = button == GLFW_MOUSE_BUTTON_LEFT ? gui::Pointer::Button::Left
        : button == GLFW_MOUSE_BUTTON_MIDDLE                        ? gui::Pointer::Button::Middle
                                                                    : gui::Pointer::Button::Right;
    const double t = glfwGetTime() * 1000;
    if (action == GLFW_PRESS) {
        if (ImGui::GetIO().WantCaptureMouse)
            return;
        pointer_.press(b, (mods & GLFW_MOD_SHIFT) != 0, x, y, t, nav_->view());
    } else if (action == GLFW_RELEASE) {
        const OrbitView before = nav_->view();
        if (auto stroke = pointer_.release(b, x, y, t, *nav_)) {
            released_ = std::move(stroke);
            releasedAt_ = glfwGetTime();
        }
        if (!sketch::operator==(before, nav_->view()))
            viewDirty_ = true;
    }
}

void App::onCursor(double x, double y)
{
    inputSeen_ = true;
    if (!nav_)
        return;
    const OrbitView before = nav_->view();
    pointer_.move(x, y, glfwGetTime() * 1000, *nav_);
    if (!sketch::operator==(before, nav_->view()))
        viewDirty_ = true;
}

void App::onScroll(double steps)
{
    inputSeen_ = true;
    if (!nav_ || ImGui::GetIO().WantCaptureMouse)
        return;
    nav_->zoom(steps);
    viewDirty_ = true;
}

void App::onKey(int key, int action, int mods)
{
    inputSeen_ = true;
    if (trace_)
        std::cout << "trace: key " << key << " action " << action << " mods " << mods << std::endl;
    if (action != GLFW_PRESS && action != GLFW_REPEAT)
        return;
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0, shift = (mods & GLFW_MOD_SHIFT) != 0;
    if (ctrl && key == GLFW_KEY_Q) {
        quit_ = true;
        return;
    }
    if (!doc_ || recovery_ || ImGui::GetIO().WantTextInput)
        return;
    if (ctrl && key == GLFW_KEY_Z) {
        shift ? redo() : undo();
    } else if (ctrl && key == GLFW_KEY_Y) {
        redo();
    } else if (ctrl && key == GLFW_KEY_S) {
        save(sessionPath_);
    } else if (ctrl && key == GLFW_KEY_O) {
        open(sessionPath_);
    } else if (ctrl && key == GLFW_KEY_E) {
        exportFace(exportPath_);
    } else if (ctrl && key == GLFW_KEY_G) {
        exportAnimation(glbPath_);
    } else if (!ctrl && key == GLFW_KEY_TAB && action == GLFW_PRESS) {
        setPoseMode(!poseMode_);
    } else if (!ctrl && poseMode_ && (key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT)) {
        // One frame at the frame rate, on the frame grid.
        setTime(std::max(0.0, (std::round(time_ * fps_) + (key == GLFW_KEY_RIGHT ? 1 : -1)) / fps_));
    } else if (!ctrl && poseMode_ && (key == GLFW_KEY_UP || key == GLFW_KEY_DOWN)) {
        setTime(std::max(0.0, time_ + (key == GLFW_KEY_UP ? 1.0 : -1.0)));
    } else if (!ctrl && poseMode_ && key == GLFW_KEY_K && action == GLFW_PRESS) {
        addKeyframe();
    } else if (!ctrl && poseMode_ && key == GLFW_KEY_M && action == GLFW_PRESS) {
        moveKeyframe();
    } else if (!ctrl && poseMode_ && key == GLFW_KEY_DELETE && action == GLFW_PRESS) {
        deleteKeyframe();
    } else if (!ctrl && poseMode_ && key == GLFW_KEY_SPACE && action == GLFW_PRESS) {
        togglePlay();
    } else if (!ctrl && poseMode_ && key == GLFW_KEY_A && action == GLFW_PRESS) {
        alternative_ = !alternative_;
    } else if (!ctrl && action == GLFW_PRESS) {
        const char preset = key == GLFW_KEY_1 || key == GLFW_KEY_KP_1 ? '1'
            : key == GLFW_KEY_3 || key == GLFW_KEY_KP_3               ? '3'
            : key == GLFW_KEY_7 || key == GLFW_KEY_KP_7               ? '7'
                                                                      : 0;
        if (preset && nav_->preset(preset))
            viewDirty_ = true;
        else if (key == GLFW_KEY_5 || key == GLFW_KEY_KP_5)
            nav_->toggleProjection(), viewDirty_ = true;
        else if (key == GLFW_KEY_HOME)
            nav_->reset(), viewDirty_ = true;
        else if (key == GLFW_KEY_O)
            showOverlay_ = !showOverlay_, overlayStale_ = true;
        else if (key == GLFW_KEY_C)
            showContours_ = !showContours_, viewDirty_ = true;
    }
}

void App::applyStroke(const sketch::Stroke& stroke)
{
    if (poseMode_) {
        applyPoseStroke(stroke);
        return;
    }
    sketch::StrokeAction a;
    a.stroke = stroke;
    a.stroke.surface = static_cast<sketch::Surface>(surface_);
    a.reading.mapper = sketch::sessionMapperNames()[static_cast<size_t>(mapper_)];
    a.reading.correlation = correlation_;
    a.reading.symmetry = symmetry_;
    sketch::ReplayOutcome out;
    try {
        out = doc_->addStroke(a);
    } catch (const Error& e) {
        say(std::string("stroke not applied: ") + e.what());
        return;
    }
    std::ostringstream text;
    text << std::fixed << std::setprecision(0);
    if (out.kind == sketch::ReplayOutcome::Kind::Refused) {
        text << "stroke refused: " << out.error;
    } else if (out.kind == sketch::ReplayOutcome::Kind::PinsNothing) {
        text << "the stroke pins nothing" << (out.reading.message.empty() ? "" : ": " + out.reading.message);
    } else {
        text << "stroke " << doc_->appliedCount() << ": " << out.reading.observations.size() << " vertices mapped, read " << out.readMs
             << " ms, rebuilt " << out.applyMs << " ms";
        flashUntil_ = glfwGetTime() + 0.8;
        faceChanged();
    }
    say(text.str());
    std::cout << "gui: " << text.str() << std::endl;
}

void App::undo()
{
    const bool reopens = doc_->undoReopens();
    bool undone = false;
    try {
        undone = doc_->undo();
    } catch (const std::exception& e) {
        say(std::string("not undone: ") + e.what());
        return;
    }
    if (undone && reopens) {
        say("undone the open: back to the work before it, " + std::to_string(doc_->appliedCount()) + " strokes, "
            + std::to_string(doc_->poseAppliedCount()) + " pose actions in effect (Ctrl+Shift+Z opens it again)");
        std::cout << "gui: undone the open, " << doc_->appliedCount() << " strokes in effect, " << doc_->poseAppliedCount()
                  << " pose actions" << std::endl;
        timelineShown_ = false;
        faceChanged();
    } else if (undone) {
        say("undone: " + std::to_string(doc_->appliedCount()) + " strokes, " + std::to_string(doc_->poseAppliedCount())
            + " pose actions in effect");
        std::cout << "gui: undone, " << doc_->appliedCount() << " strokes in effect, " << doc_->poseAppliedCount() << " pose actions"
                  << std::endl;
        timelineShown_ = false;
        faceChanged();
    }
}

void App::redo()
{
    try {
        if (!doc_->redo())
            return;
    } catch (const std::exception& e) {
        say(std::string("not redone: ") + e.what());
        return;
    }
    say("redone: " + std::to_string(doc_->appliedCount()) + " strokes, " + std::to_string(doc_->poseAppliedCount())
        + " pose actions in effect");
    std::cout << "gui: redone, " << doc_->appliedCount() << " strokes in effect, " << doc_->poseAppliedCount() << " pose actions"
              << std::endl;
    timelineShown_ = false;
    faceChanged();
}

void App::setPoseMode(bool on)
{
    if (on == poseMode_)
        return;
    if (on) {
        try {
            doc_->preparePosing();
        } catch (const std::exception& e) {
            say(std::string("no pose mode: ") + e.what());
            std::cout << "gui: no pose mode: " << e.what() << std::endl;
            return;
        }
    }
    poseMode_ = on;
    playing_ = false;
    std::cout << "gui: " << (on ? "pose" : "sketch") << " mode" << std::endl;
    say(on ? "pose mode: strokes pose the face (Tab: back to sketching)" : "sketch mode");
    faceChanged();
}

void App::addPoseAction(const sketch::PoseAction& action, const std::string& what)
{
    try {
        doc_->addPoseAction(action);
    } catch (const std::exception& e) {
        say(what + " not applied: " + e.what());
        std::cout << "gui: " << what << " not applied: " << e.what() << std::endl;
        return;
    }
    faceChanged();
}

void App::applyPoseStroke(const sketch::Stroke& stroke)
{
    sketch::PoseAction a;
    a.kind = sketch::PoseActionKind::Stroke;
    a.stroke = stroke;
    a.stroke.surface = sketch::Surface::Face; // cast onto the face as posed now (pose_session.h)
    a.alternative = alternative_;
    const size_t before = doc_->poseAppliedCount();
    addPoseAction(a, "pose stroke");
    if (doc_->poseAppliedCount() == before)
        return;
    timelineShown_ = false;
    const pose::PoseEditor& e = *doc_->poseEditor();
    std::ostringstream text;
    text << "pose stroke: " << e.reading().fps.size() << " feature points (";
    for (size_t i = 0; i < e.reading().fps.size(); ++i)
        text << (i ? " " : "") << e.reading().fps[i].name;
    text << "), " << (a.alternative ? "alternative" : "primary") << " interpretation, component " << e.component();
    say(text.str());
    std::cout << "gui: " << text.str() << std::endl;
}

void App::addKeyframe()
{
    if (!doc_->posingEnabled()) {
        say("keyframes need a pose model (--poses)");
        return;
    }
    sketch::PoseAction a;
    a.kind = sketch::PoseActionKind::Keyframe;
    // On the frame grid, so that playback and the glTF export meet the keyframe exactly.
    a.time = std::round(time_ * fps_) / fps_;
    const size_t before = doc_->poseAppliedCount();
    addPoseAction(a, "keyframe");
    if (doc_->poseAppliedCount() == before)
        return;
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << "keyframe at " << a.time << " s (" << doc_->poseEditor()->keyframes().size()
         << " keyframes)";
    say(text.str());
    std::cout << "gui: " << text.str() << std::endl;
}

void App::moveKeyframe()
{
    if (std::isnan(selectedKey_)) {
        say("select a keyframe first (its button in the timeline panel)");
        return;
    }
    sketch::PoseAction a;
    a.kind = sketch::PoseActionKind::MoveKeyframe;
    a.time = selectedKey_;
    a.to = std::round(time_ * fps_) / fps_; // on the frame grid, as addKeyframe
    const size_t before = doc_->poseAppliedCount();
    addPoseAction(a, "keyframe move");
    if (doc_->poseAppliedCount() == before)
        return;
    selectedKey_ = a.to;
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << "keyframe moved from " << a.time << " s to " << a.to << " s";
    say(text.str());
    std::cout << "gui: " << text.str() << std::endl;
}

void App::deleteKeyframe()
{
    // Without a selection, the keyframe under the time cursor.
    if (const pose::PoseEditor* e = doc_->poseEditor(); std::isnan(selectedKey_) && e && doc_->poseAppliedCount() > 0)
        for (const pose::Keyframe& k : e->keyframes())
            if (k.time == std::round(time_ * fps_) / fps_)
                selectedKey_ = k.time;
    if (std::isnan(selectedKey_)) {
        say("select a keyframe first (its button in the timeline panel)");
        return;
    }
    sketch::PoseAction a;
    a.kind = sketch::PoseActionKind::DeleteKeyframe;
    a.time = selectedKey_;
    const size_t before = doc_->poseAppliedCount();
    addPoseAction(a, "keyframe delete");
    if (doc_->poseAppliedCount() == before)
        return;
    selectedKey_ = std::numeric_limits<double>::quiet_NaN();
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << "keyframe at " << a.time << " s deleted";
    say(text.str());
    std::cout << "gui: " << text.str() << std::endl;
}

void App::switchInterpretation()
{
    // The last pose stroke read again with the other completion mixture (thesis figs. 5.10,
    // 5.11): undo it and draw it again with the flag flipped, so both stay in the history.
    const auto& actions = doc_->poseActions();
    const size_t n = doc_->poseAppliedCount();
    if (n == 0 || actions[n - 1].kind != sketch::PoseActionKind::Stroke) {
        say("the last pose action is not a pose stroke");
        return;
    }
    sketch::PoseAction a = actions[n - 1];
    a.alternative = !a.alternative;
    alternative_ = a.alternative;
    doc_->undo();
    try {
        doc_->addPoseAction(a);
        say(std::string("the last pose stroke now reads with the ") + (a.alternative ? "alternative" : "primary") + " interpretation");
        std::cout << "gui: switched to the " << (a.alternative ? "alternative" : "primary") << " interpretation" << std::endl;
    } catch (const std::exception& e) {
        doc_->redo();
        say(std::string("not switched: ") + e.what());
    }
    timelineShown_ = false;
    faceChanged();
}

void App::setTime(double seconds)
{
    time_ = seconds;
    playing_ = false;
    timelineShown_ = timeline_ != nullptr;
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << "time " << time_ << " s";
    std::cout << "gui: " << text.str() << std::endl;
    showFrame();
}

void App::togglePlay()
{
    if (!timeline_) {
        say("the timeline needs two keyframes (K adds one at the current time)");
        return;
    }
    playing_ = !playing_;
    lastTick_ = -1;
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << (playing_ ? "playing from " : "paused at ") << time_ << " s";
    std::cout << "gui: " << text.str() << std::endl;
    if (!playing_)
        showFrame();
}

void App::advancePlayback(double now)
{
    if (!playing_ || !timeline_) {
        lastTick_ = -1;
        return;
    }
    if (lastTick_ >= 0)
        time_ += now - lastTick_;
    lastTick_ = now;
    if (time_ < timeline_->begin())
        time_ = timeline_->begin();
    if (time_ > timeline_->end()) {
        if (loop_) {
            time_ = timeline_->begin() + std::fmod(time_ - timeline_->begin(), timeline_->end() - timeline_->begin());
        } else {
            time_ = timeline_->end();
            playing_ = false;
        }
    }
    timelineShown_ = true;
    showFrame();
}

void App::showFrame()
{
    if (!player_ || !timelineShown_)
        return;
    // Played at the frame rate: the frame at or before time_, inside the timeline.
    const double t = std::clamp(
        timeline_->begin() + std::floor((time_ - timeline_->begin()) * fps_ + 1e-9) / fps_, timeline_->begin(), timeline_->end());
    if (t == frameTime_ && frame_.rows() > 0)
        return;
    try {
        player_->frame(t, frame_);
        frameTime_ = t;
    } catch (const std::exception& e) {
        say(std::string("timeline: ") + e.what());
        return;
    }
    scene_->updateMesh(faceItem_, frame_);
    // While playing, the contours (curvature and the contour pass on the CPU, several times the
    // rest of a frame at 6,000 vertices) are hidden and drawn again for the frame playback stops on.
    if (playing_) {
        scene_->setVisible(contourItem_, false);
        contoursStale_ = true;
        return;
    }
    curvature_ = estimateCurvature(contourFace());
    viewDirty_ = true;
    contoursStale_ = false;
}

void App::poseChanged()
{
    // The timeline through the keyframes in effect, and the points of the current pose.
    player_.reset();
    timeline_.reset();
    frame_.resize(0, 3);
    frameTime_ = -1;
    const pose::PoseEditor* e = doc_->poseEditor();
    if (e && doc_->poseAppliedCount() > 0 && e->keyframes().size() >= 2) {
        timeline_ = std::make_unique<pose::Timeline>(e->timeline(doc_->tension()));
        player_ = std::make_unique<pose::TimelinePlayer>(*loaded_->poseModel, *timeline_, e->neutral());
    } else {
        playing_ = false;
        timelineShown_ = false;
    }
    std::vector<glm::vec3> fps, hits;
    if (poseMode_ && e && doc_->poseAppliedCount() > 0) {
        // Lifted 1 mm off the surface along its normal: points are depth tested, and a point on
        // the surface would be half hidden by it.
        const Vertices p = e->featurePointPositions();
        const Vertices normals = vertexNormals(e->face());
        const auto& fpVertex = loaded_->poseModel->fps.vertices;
        auto lifted
            = [&](const Eigen::Vector3d& x, int fp) { return toVec3(x + normals.row(fpVertex[static_cast<size_t>(fp)]).transpose()); };
        for (Eigen::Index i = 0; i < p.rows(); ++i)
            fps.push_back(lifted(p.row(i).transpose(), static_cast<int>(i)));
        for (const pose::IdentifiedFp& fp : e->reading().fps)
            hits.push_back(lifted(fp.position, fp.fp));
    }
    scene_->setPoints(fpItem_, fps, { { 0.15f, 0.35f, 0.95f, 1 } });
    scene_->setPoints(hitItem_, hits, { { 0.95f, 0.45f, 0.05f, 1 } });
}

void App::exportAnimation(const fs::path& path)
{
    try {
        if (!timeline_)
            fail("the timeline needs two keyframes (K adds one at the current time)");
        if (path.extension() != ".glb")
            fail(path.string(), ": the animation is written as .glb, not '", path.extension().string(), "'");
        const pose::PoseEditor& e = *doc_->poseEditor();
        const std::vector<double> times = pose::frameTimes(*timeline_, fps_);
        writeGlb(path, pose::timelineAnimation(*loaded_->poseModel, *timeline_, e.neutral(), times));
        say("exported " + path.string());
        std::cout << "gui: exported " << path.string() << " (" << times.size() << " frames at " << fps_ << " fps)" << std::endl;
    } catch (const std::exception& e) {
        say(std::string("not exported: ") + e.what());
        std::cout << "gui: animation not exported: " << e.what() << std::endl;
    }
}

void App::save(const fs::path& path)
{
    try {
        doc_->save(path);
        doc_->markSaved();
        say("saved " + path.string());
        std::cout << "gui: saved " << path.string() << " (" << doc_->appliedCount() << " strokes)";
        if (doc_->poseAppliedCount() > 0)
            std::cout << " with " << doc_->poseAppliedCount() << " pose actions";
        std::cout << std::endl;
    } catch (const std::exception& e) {
        say(std::string("not saved: ") + e.what());
    }
}

void App::open(const fs::path& path)
{
    try {
        const int dropped = doc_->open(path);
        doc_->markSaved();
        say("opened " + path.string() + (dropped ? " (" + std::to_string(dropped) + " strokes pinned nothing)" : ""));
        std::cout << "gui: opened " << path.string() << " (" << doc_->appliedCount() << " strokes)" << std::endl;
        faceChanged();
    } catch (const std::exception& e) {
        say(std::string("not opened: ") + e.what());
    }
}

void App::exportFace(const fs::path& path)
{
    try {
        doc_->exportMesh(path);
        say("exported " + path.string());
        std::cout << "gui: exported " << path.string() << std::endl;
    } catch (const std::exception& e) {
        say(std::string("not exported: ") + e.what());
    }
}

void App::faceChanged()
{
    const Mesh face = doc_->face();
    poseChanged();
    showFrame();
    scene_->updateMesh(faceItem_, displayMesh().V);
    curvature_ = estimateCurvature(contourFace());
    if (!loaded_->data->trainNames.empty()) {
        // The training faces are the first of the candidates: searched in place, not copied (a
        // copy of 250 faces cost tens of ms after every stroke).
        const std::span<const Mesh> train(loaded_->data->candidateFaces.data(), loaded_->data->trainNames.size());
        similar_.clear();
        for (const auto& [index, mm] : sketch::mostSimilarFaces(face, train, 3))
            similar_.push_back({ loaded_->data->trainNames[static_cast<size_t>(index)], mm });
    }
    // Stroke items: one per stroke drawn (undone ones hidden).
    for (DrawId id : strokeItems_)
        scene_->remove(id);
    for (DrawId id : interpretedItems_)
        scene_->remove(id);
    strokeItems_.clear();
    interpretedItems_.clear();
    std::vector<glm::vec3> flash;
    for (size_t i = 0; i < doc_->appliedCount(); ++i) {
        const gui::DocumentStroke& s = doc_->strokes()[i];
        std::vector<glm::vec3> drawn, interpreted;
        for (size_t k = 1; k < s.reading.worldPoints.size(); ++k) {
            drawn.push_back(toVec3(s.reading.worldPoints[k - 1]));
            drawn.push_back(toVec3(s.reading.worldPoints[k]));
        }
        const sketch::InterpretedStroke is = sketch::interpretStroke(s.reading, face, orbitCamera(s.action.stroke.view));
        for (size_t k = 1; k < is.world.size(); ++k) {
            interpreted.push_back(toVec3(is.world[k - 1]));
            interpreted.push_back(toVec3(is.world[k]));
        }
        if (i + 1 == doc_->appliedCount())
            for (const Eigen::Vector3d& p : is.world)
                flash.push_back(toVec3(p));
        strokeItems_.push_back(scene_->addLines(drawn, { { 0.85f, 0.1f, 0.1f, 1 } }, { 2.0f, false }));
        interpretedItems_.push_back(scene_->addLines(interpreted, { { 0.1f, 0.25f, 0.95f, 1 } }, { 2.0f, true }));
    }
    scene_->setPoints(flashItem_, flash, { { 0.1f, 0.85f, 0.2f, 1 } });
    viewDirty_ = true;
}

void App::updateStrokeItems()
{
    // Strokes show fully in the view they were drawn in and fade within 30 degrees of it (4.7.2).
    const glm::dvec3 now = viewDirection(nav_->view());
    for (size_t i = 0; i < strokeItems_.size(); ++i) {
        const gui::DocumentStroke& s = doc_->strokes()[i];
        const double angle = glm::degrees(std::acos(std::clamp(glm::dot(now, viewDirection(s.action.stroke.view)), -1.0, 1.0)));
        const float alpha = static_cast<float>(std::max(0.12, 1.0 - angle / 30.0));
        std::vector<glm::vec3> drawn;
        for (size_t k = 1; k < s.reading.worldPoints.size(); ++k) {
            drawn.push_back(toVec3(s.reading.worldPoints[k - 1]));
            drawn.push_back(toVec3(s.reading.worldPoints[k]));
        }
        scene_->setLines(strokeItems_[i], drawn, { { 0.85f, 0.1f, 0.1f, alpha } });
        // Shape strokes lie on the unposed face: hidden in pose mode.
        scene_->setVisible(strokeItems_[i], showStrokes_ && !poseMode_);
        scene_->setVisible(interpretedItems_[i], showStrokes_ && !poseMode_);
    }
}

void App::viewChanged()
{
    const Camera camera = orbitCamera(nav_->view());
    // (curvature_ is of another face than the one shown while the contours are stale.)
    if (showContours_ && !contoursStale_) {
        const ContourLines lines = contourLines(contourFace(), curvature_, camera, contourParams_, loaded_->data->flags);
        std::vector<glm::vec3> all = lines.silhouette;
        all.insert(all.end(), lines.suggestive.begin(), lines.suggestive.end());
        scene_->setLines(contourItem_, all, { { 0.08f, 0.08f, 0.1f, 1 } });
    }
    scene_->setVisible(contourItem_, showContours_ && !contoursStale_);
    updateStrokeItems();
    overlayStale_ = true;
    overlayQuietFrames_ = 0;
    if (c_.printGuides)
        printGuides();
}

void App::updateOverlay()
{
    if (!showOverlay_) {
        scene_->clearOverlay();
        return;
    }
    const Camera camera = orbitCamera(nav_->view());
    scene_->setOverlay(gui::heatImage(loaded_->cloud->candidates(camera), camera.width, camera.height));
    overlayStale_ = false;
}

void App::printGuides()
{
    // For scripted input (tests/gui): where the upper lip and the nose profile of the current
    // face are in the window, in screen coordinates (GLFW's, what xdotool moves to).
    const Camera camera = orbitCamera(nav_->view());
    const Mesh face = contourFace();
    const double s = window_.contentScale();
    auto print = [&](const std::string& name, const std::vector<int>& vertices) {
        std::cout << "guide " << name << " view " << nav_->view().angles.azimuthDeg << "," << nav_->view().angles.elevationDeg << ":";
        for (int v : vertices) {
            const glm::dvec3 p = camera.project({ face.V(v, 0), face.V(v, 1), face.V(v, 2) });
            std::cout << " " << std::lround(p.x / s) << "," << std::lround(p.y / s);
        }
        std::cout << std::endl;
    };
    const auto& contours = loaded_->data->contours;
    if (auto it = contours.find("lip_upper_outer"); it != contours.end())
        print("upper_lip", it->second);
    std::vector<int> nose;
    for (const char* name : { "n", "s", "cs1", "prn", "sn" })
        if (auto it = loaded_->data->landmarks.find(name); it != loaded_->data->landmarks.end())
            nose.push_back(it->second);
    print("nose_profile", nose);
}

void App::panels()
{
    const float scale = static_cast<float>(window_.contentScale());
    if (job_) {
        ImGui::SetNextWindowPos({ 20 * scale, 20 * scale }, ImGuiCond_Always);
        ImGui::SetNextWindowSize({ 420 * scale, 0 }, ImGuiCond_Always);
        ImGui::Begin("Working", nullptr, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoResize);
        ImGui::TextUnformatted(job_->name().c_str());
        ImGui::ProgressBar(static_cast<float>(job_->fraction()), { -1, 0 }, job_->stage().c_str());
        if (ImGui::Button("Cancel"))
            job_->cancel();
        ImGui::End();
    }
    if (!doc_)
        return;

    ImGui::SetNextWindowPos({ 10 * scale, 10 * scale }, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({ 330 * scale, 0 }, ImGuiCond_FirstUseEver);
    ImGui::Begin("Sketch");
    if (ImGui::RadioButton("sketch", !poseMode_))
        setPoseMode(false);
    ImGui::SameLine();
    ImGui::BeginDisabled(!doc_->posingEnabled());
    if (ImGui::RadioButton("pose (Tab)", poseMode_))
        setPoseMode(true);
    ImGui::EndDisabled();
    if (!doc_->posingEnabled()) { // wrapped on lines of its own: beside the buttons it ran past the panel's edge
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
        ImGui::TextWrapped("no pose model: start the app with --poses POSES.model");
        ImGui::PopStyleColor();
    }
    if (!poseMode_) {
        static const char* mappers[] = { "nearest", "heuristic", "hmm (4.8)", "simple" };
        ImGui::Combo("mapper", &mapper_, mappers, 4);
        static const char* surfaces[] = { "face", "front plane", "profile plane", "paper" };
        ImGui::Combo("projection", &surface_, surfaces, 4);
        ImGui::Checkbox("correlation", &correlation_);
        ImGui::SameLine();
        ImGui::Checkbox("symmetry", &symmetry_);
    } else {
        ImGui::Checkbox("alternative interpretation (A)", &alternative_);
        if (ImGui::Button("switch last stroke's"))
            switchInterpretation();
        ImGui::SameLine();
        if (ImGui::Button("clear pose")) {
            sketch::PoseAction a;
            a.kind = sketch::PoseActionKind::Clear;
            addPoseAction(a, "clear");
        }
        if (const pose::PoseEditor* e = doc_->poseEditor(); e && doc_->poseAppliedCount() > 0)
            ImGui::Text("%zu FPs drawn (orange); completed (blue)", e->reading().fps.size());
    }
    if (ImGui::Checkbox("contours (C)", &showContours_))
        viewDirty_ = true;
    ImGui::SameLine();
    if (ImGui::Checkbox("overlay (O)", &showOverlay_))
        overlayStale_ = true;
    ImGui::SameLine();
    if (ImGui::Checkbox("strokes", &showStrokes_))
        viewDirty_ = true;
    if (ImGui::Button("front (1)"))
        nav_->preset('1'), viewDirty_ = true;
    ImGui::SameLine();
    if (ImGui::Button("profile (3)"))
        nav_->preset('3'), viewDirty_ = true;
    ImGui::SameLine();
    if (ImGui::Button("3/4 (7)"))
        nav_->preset('7'), viewDirty_ = true;
    ImGui::SameLine();
    if (ImGui::Button("reset"))
        nav_->reset(), viewDirty_ = true;
    bool persp = nav_->view().kind == Projection::Perspective;
    if (ImGui::Checkbox("perspective (5)", &persp))
        nav_->toggleProjection(), viewDirty_ = true;
    ImGui::Separator();
    ImGui::BeginDisabled(!doc_->canUndo());
    if (ImGui::Button("undo"))
        undo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!doc_->canRedo());
    if (ImGui::Button("redo"))
        redo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::Text("%zu strokes, %zu pose actions%s", doc_->appliedCount(), doc_->poseAppliedCount(),
        doc_->revision() != doc_->savedRevision() ? " (unsaved)" : "");
    ImGui::TextWrapped("%s", status_.c_str());
    if (!similar_.empty()) {
        ImGui::Separator();
        ImGui::TextUnformatted("most similar training faces:");
        for (const auto& [name, mm] : similar_)
            ImGui::BulletText("%s  %.2f mm", name.c_str(), mm);
    }
    ImGui::Separator();
    ImGui::InputText("session", sessionPath_, sizeof sessionPath_);
    if (ImGui::Button("save (Ctrl+S)"))
        save(sessionPath_);
    ImGui::SameLine();
    if (ImGui::Button("open (Ctrl+O)"))
        open(sessionPath_);
    ImGui::InputText("face", exportPath_, sizeof exportPath_);
    if (ImGui::Button("export .ply/.obj (Ctrl+E)"))
        exportFace(exportPath_);
    ImGui::InputText("animation", glbPath_, sizeof glbPath_);
    ImGui::BeginDisabled(!timeline_);
    if (ImGui::Button("export glTF animation .glb (Ctrl+G)"))
        exportAnimation(glbPath_);
    ImGui::EndDisabled();
    if (!autosave_->lastError().empty())
        ImGui::TextWrapped("autosave failed: %s", autosave_->lastError().c_str());
    ImGui::End();

    if (poseMode_)
        timelinePanel();

    // Top right, away from the sketch panel: below it, a taller panel (a wrapped hint, more similar
    // faces) reached it at small window heights. Collapsed until a user wants other data.
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos({ display.x - 10 * scale, 10 * scale }, ImGuiCond_FirstUseEver, { 1, 0 });
    ImGui::SetNextWindowSize({ 420 * scale, 0 }, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
    ImGui::Begin("Data");
    ImGui::InputText("model", modelPath_, sizeof modelPath_);
    ImGui::InputText("dataset", datasetPath_, sizeof datasetPath_);
    ImGui::BeginDisabled(job_ != nullptr);
    if (ImGui::Button("load"))
        startLoad(modelPath_, datasetPath_, loaded_ ? loaded_->posesPath : fs::path(), false);
    ImGui::SameLine();
    if (ImGui::Button("train model on dataset, then load"))
        startTrain(datasetPath_, modelPath_);
    ImGui::EndDisabled();
    ImGui::End();

    // The recovery offer, after the windows it blocks.
    if (recovery_) {
        if (!ImGui::IsPopupOpen("Restore?"))
            ImGui::OpenPopup("Restore?");
        if (ImGui::BeginPopupModal("Restore?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
            ImGui::Text("The last session was not saved: %zu strokes were autosaved to", recovery_->actions.size());
            ImGui::TextUnformatted(autosave_->file().string().c_str());
            if (ImGui::Button("Restore")) {
                try {
                    doc_->load(*recovery_, autosave_->file(), autosave_->file().string());
                    say("restored " + std::to_string(doc_->appliedCount()) + " strokes");
                } catch (const std::exception& e) {
                    say(std::string("not restored: ") + e.what());
                }
                recovery_.reset();
                faceChanged();
                ImGui::CloseCurrentPopup();
            }
            ImGui::SameLine();
            if (ImGui::Button("Discard")) {
                recovery_.reset();
                ImGui::CloseCurrentPopup();
            }
            ImGui::EndPopup();
        }
    }
}

void App::timelinePanel()
{
    const float scale = static_cast<float>(window_.contentScale());
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos({ 360 * scale, display.y - 150 * scale }, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({ std::max(display.x - 380 * scale, 300 * scale), 0 }, ImGuiCond_FirstUseEver);
    ImGui::Begin("Timeline");
    const pose::PoseEditor* e = doc_->poseEditor();
    const std::vector<pose::Keyframe> none;
    const std::vector<pose::Keyframe>& keys = e && doc_->poseAppliedCount() > 0 ? e->keyframes() : none;
    double last = 0;
    for (const pose::Keyframe& k : keys)
        last = std::max(last, k.time);
    float t = static_cast<float>(time_);
    ImGui::SetNextItemWidth(-80 * scale);
    if (ImGui::SliderFloat("time (s)", &t, 0.0f, static_cast<float>(std::max(last + 1.0, 2.0)), "%.3f"))
        setTime(std::round(static_cast<double>(t) * fps_) / fps_);
    // The keyframes as marks under the slider.
    {
        ImDrawList* draw = ImGui::GetWindowDrawList();
        const ImVec2 p = ImGui::GetCursorScreenPos();
        const float width = ImGui::GetContentRegionAvail().x - 80 * scale;
        const float range = static_cast<float>(std::max(last + 1.0, 2.0));
        for (const pose::Keyframe& k : keys) {
            const float x = p.x + width * static_cast<float>(k.time) / range;
            draw->AddTriangleFilled(
                { x, p.y }, { x - 5 * scale, p.y + 9 * scale }, { x + 5 * scale, p.y + 9 * scale }, IM_COL32(240, 150, 20, 255));
        }
        const float x = p.x + width * static_cast<float>(time_) / range;
        draw->AddLine({ x, p.y }, { x, p.y + 10 * scale }, IM_COL32(40, 90, 240, 255), 2 * scale);
        ImGui::Dummy({ width, 11 * scale });
    }
    if (ImGui::Button("add keyframe (K)"))
        addKeyframe();
    ImGui::SameLine();
    ImGui::BeginDisabled(!timeline_);
    if (ImGui::Button(playing_ ? "pause (Space)" : "play (Space)"))
        togglePlay();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::Checkbox("loop", &loop_);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(110 * scale);
    int rate = static_cast<int>(std::lround(fps_));
    if (ImGui::InputInt("fps", &rate, 1, 10))
        fps_ = std::clamp(rate, 1, 240), frameTime_ = -1;
    ImGui::SameLine();
    ImGui::Checkbox("show timeline", &timelineShown_);
    if (!keys.empty()) {
        ImGui::TextUnformatted("keyframes:");
        bool selectedExists = false;
        for (size_t i = 0; i < keys.size(); ++i) {
            ImGui::SameLine();
            char label[32];
            const bool selected = keys[i].time == selectedKey_;
            selectedExists = selectedExists || selected;
            std::snprintf(label, sizeof label, "%s%.2f s##k%zu", selected ? "> " : "", keys[i].time, i);
            if (ImGui::SmallButton(label)) {
                selectedKey_ = keys[i].time; // selects it: the buttons below act on it
                setTime(keys[i].time);
            }
        }
        if (!selectedExists) // undone, deleted or moved by undo/redo
            selectedKey_ = std::numeric_limits<double>::quiet_NaN();
        ImGui::BeginDisabled(!selectedExists);
        ImGui::SameLine();
        if (ImGui::SmallButton("move selected here (M)"))
            moveKeyframe();
        ImGui::SameLine();
        if (ImGui::SmallButton("delete selected (Del)"))
            deleteKeyframe();
        ImGui::EndDisabled();
    } else {
        ImGui::TextDisabled("no keyframes: pose the face with strokes, then K adds the pose at the current time");
    }
    ImGui::End();
    if (timelineShown_)
        showFrame();
    else if (frameTime_ >= 0) {
        frameTime_ = -1;
        scene_->updateMesh(faceItem_, displayMesh().V);
        curvature_ = estimateCurvature(contourFace());
        viewDirty_ = true;
    }
}

namespace {

double processCpuSeconds()
{
    timespec t {};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// The same view, field by field (a moved view differs in at least one).
bool sameView(const OrbitView& a, const OrbitView& b)
{
    return a.target == b.target && a.angles.azimuthDeg == b.angles.azimuthDeg && a.angles.elevationDeg == b.angles.elevationDeg
        && a.distance == b.distance && a.kind == b.kind && a.halfHeight == b.halfHeight && a.fovY == b.fovY && a.nearPlane == b.nearPlane
        && a.farPlane == b.farPlane && a.width == b.width && a.height == b.height;
}

} // namespace

void App::run()
{
    const float background[4] = { 0.93f, 0.93f, 0.94f, 1 };
    std::vector<double> frameMs;
    std::optional<double> strokeToFrameMs;
    std::optional<sketch::Stroke> benchStroke;
    std::optional<double> benchReleasedAt;
    double lastFrameStart = -1;
    double cpuAtFrame11 = 0;
    bool capture = false, shotTaken = false;
    for (;;) {
        // An idle app does not redraw: after a few frames in which nothing changed (ImGui settles
        // in two) it sleeps until an input event, waking every quarter second for the autosave.
        // Scripted runs count frames and always draw.
        const bool scripted = c_.benchFrames > 0 || c_.quitAfterFrames > 0;
        if (!scripted && idleFrames_ >= 3) {
            glfwWaitEventsTimeout(0.25);
            // Woken by the timeout, with no input and the same window size: nothing to draw.
            int fw = 0, fh = 0;
            glfwGetFramebufferSize(window_.glfw(), &fw, &fh);
            const bool resized = nav_ && (fw != nav_->view().width || fh != nav_->view().height);
            if (!inputSeen_ && !resized && !quit_ && !window_.shouldClose() && !job_) {
                if (doc_)
                    autosave_->tick(*doc_, glfwGetTime());
                continue;
            }
        } else
            glfwPollEvents();
        pollJob();
        // Quitting draws one more frame when it is to be captured (--screenshot).
        const bool quitting = quit_ || window_.shouldClose();
        if (quitting && (c_.screenshot.empty() || shotTaken || !doc_))
            break;
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_.glfw(), &w, &h);
        const double now = glfwGetTime();
        // What changed since the last frame (before this frame's work clears it).
        const bool busy = inputSeen_ || !doc_ || job_ || viewDirty_ || released_ || playing_ || now < flashUntil_ + 0.2
            || (showOverlay_ && overlayStale_) || contoursStale_ || recovery_ || reducedShown_;
        inputSeen_ = false;
        idleFrames_ = busy ? 0 : idleFrames_ + 1;

        if (doc_) {
            if (w > 0 && h > 0 && (w != nav_->view().width || h != nav_->view().height)) {
                nav_->resize(w, h);
                viewDirty_ = true;
            }
            // The benchmark: orbit once around the face; half way, one scripted stroke.
            if (c_.benchFrames > 0) {
                const double f = static_cast<double>(readyFrames_) / c_.benchFrames;
                if (readyFrames_ == 0) {
                    // The scripted stroke is simulated before the measured frames: a user's
                    // stroke costs nothing until its release.
                    sketch::SimulateOptions o;
                    o.imageSize = std::min(w, h);
                    const Mesh& target = loaded_->data->testFaces.empty() ? loaded_->data->candidateFaces[0] : loaded_->data->testFaces[0];
                    const sketch::Simulation sim
                        = sketch::simulateStrokes(target, meanMesh(*loaded_->faceModel), loaded_->data->contours, loaded_->data->flags, o);
                    if (!sim.strokes.empty())
                        benchStroke = sim.strokes.front().stroke;
                }
                if (readyFrames_ == static_cast<std::uint64_t>(c_.benchFrames / 2)) {
                    nav_->preset('1');
                    if (benchStroke) {
                        released_ = std::move(*benchStroke);
                        benchStroke.reset();
                        releasedAt_ = now;
                        benchReleasedAt = now;
                    }
                } else {
                    nav_->preset('1');
                    nav_->orbit(-360.0 * f / 0.4, 0);
                }
                viewDirty_ = true;
            }
            if (released_) {
                const sketch::Stroke s = std::move(*released_);
                released_.reset();
                applyStroke(s);
            }
            if (viewDirty_) {
                viewChanged();
                viewDirty_ = false;
                lastView_ = nav_->view();
            }
            // The overlay's cloud takes tens of ms: rebuilt once the view has rested 3 frames.
            if (showOverlay_ && overlayStale_ && ++overlayQuietFrames_ >= 3)
                updateOverlay();
            else if (!showOverlay_)
                scene_->clearOverlay();
            std::vector<glm::vec2> drawing;
            if (pointer_.drag() == gui::Pointer::Drag::Stroke)
                for (const sketch::StrokePoint& p : pointer_.stroke().points)
                    drawing.push_back({ static_cast<float>(p.x), static_cast<float>(p.y) });
            scene_->setScreenPolyline(drawingItem_, drawing, { { 0.85f, 0.1f, 0.1f, 1 } });
            scene_->setVisible(flashItem_, !poseMode_ && now < flashUntil_ && std::fmod(now * 8, 2.0) < 1.4);
            advancePlayback(now);
            if (!playing_ && contoursStale_) {
                contoursStale_ = false;
                curvature_ = estimateCurvature(contourFace());
                viewDirty_ = true;
            }
            scene_->setVisible(fpItem_, poseMode_ && !showingTimeline());
            scene_->setVisible(hitItem_, poseMode_ && !showingTimeline());
            autosave_->tick(*doc_, now);
        }

        const bool last = doc_
            && (quitting || (c_.quitAfterFrames > 0 && readyFrames_ + 1 >= static_cast<std::uint64_t>(c_.quitAfterFrames))
                || (c_.benchFrames > 0 && readyFrames_ + 1 >= static_cast<std::uint64_t>(c_.benchFrames)));
        capture = last && !c_.screenshot.empty() && !shotTaken;

        // While the view moves (it differs from the last frame's) the scene is drawn at
        // motionScale and scaled up; the first frame with the view at rest is full size again
        // (reducedShown_ keeps the loop drawing until it is), as are captured frames.
        const bool moving = doc_ && drawnView_ && !sameView(nav_->view(), *drawnView_);
        const double sceneScale = moving && !capture ? c_.motionScale : 1.0;
        gpu::Frame frame;
        if (!window_.begin(frame, background, sceneScale)) {
            window_.skipFrame();
            if (quitting)
                break;
            if (w == 0 || h == 0)
                glfwWaitEventsTimeout(0.05); // minimised: no frames until restored
            continue;
        }
        panels();
        if (doc_) {
            const VkExtent2D scene = window_.sceneExtent();
            scene_->record(frame.cmd, frame.slot, orbitCamera(nav_->view()), scene, float(scene.width) / float(frame.extent.width),
                window_.reducedFrame() ? reducedTarget_ : 0);
            drawnView_ = nav_->view();
        }
        reducedShown_ = window_.reducedFrame();
        window_.end(frame, capture);

        if (doc_) {
            if (lastFrameStart >= 0 && readyFrames_ > 10)
                frameMs.push_back((now - lastFrameStart) * 1000);
            if (readyFrames_ == 11)
                cpuAtFrame11 = processCpuSeconds();
            lastFrameStart = now;
            if (benchReleasedAt && !strokeToFrameMs) {
                // The frame with the new face has been submitted; wait for the GPU to draw it.
                window_.waitIdle();
                strokeToFrameMs = (glfwGetTime() - *benchReleasedAt) * 1000;
            }
            ++readyFrames_;
            if (trace_ && readyFrames_ % 50 == 0)
                std::cout << "trace: frame " << readyFrames_ << " at " << now << " s" << std::endl;
            if (readyFrames_ == 1)
                std::cout << "gui: first frame" << std::endl;
        }
        if (capture) {
            shotTaken = true;
            writePng(c_.screenshot, window_.screenshot());
            std::cout << "gui: wrote " << c_.screenshot << std::endl;
        }
        if (last)
            quit_ = true;
    }
    if (job_) {
        job_->cancel();
        job_.reset();
    }
    window_.waitIdle();
    if (doc_ && autosave_)
        autosave_->flush(*doc_);
    if (c_.benchFrames > 0 && doc_) {
        const long v = loaded_->faceModel->vertexCount();
        std::cout << std::fixed << std::setprecision(2);
        std::cout << "gui_frame_ms_" << v << "v " << percentile(frameMs, 0.5) << "\n";
        std::cout << "gui_frame_p95_ms_" << v << "v " << percentile(frameMs, 0.95) << "\n";
        std::cout << "gui_stroke_to_frame_ms_" << v << "v " << strokeToFrameMs.value_or(-1) << "\n";
        // CPU time of the whole process (the app's thread and lavapipe's) per measured frame:
        // steadier than the frame's wall time when other programs share the cores.
        if (readyFrames_ > 11)
            std::cout << "gui_frame_cpu_ms_" << v << "v " << (processCpuSeconds() - cpuAtFrame11) * 1000 / double(readyFrames_ - 11)
                      << "\n";
    }
    if (c_.play && doc_ && doc_->poseEditor()) {
        // Frame times while the timeline plays (each frame: spline, mapping, contours, drawing).
        const long v = doc_->poseEditor()->neutral().vertexCount();
        std::cout << std::fixed << std::setprecision(2) << "gui_play_frame_ms_" << v << "v " << percentile(frameMs, 0.5) << "\n"
                  << "gui_play_frame_p95_ms_" << v << "v " << percentile(frameMs, 0.95) << "\n";
    }
}

} // namespace

void addGuiCommand(CLI::App& root)
{
    auto c = std::make_shared<GuiCommand>();
    auto* cmd = root.add_subcommand("gui", "The interactive app: sketch a face in a window (no arguments: built-in data)");
    cmd->footer("With no arguments, opens on the built-in data (synthesised and trained once into the cache folder,\n"
                "$FACESKETCH_CACHE_DIR or ~/.cache/facesketch). Autosaves every 30 s and on exit to\n"
                "$FACESKETCH_STATE_DIR, $XDG_STATE_HOME/facesketch or ~/.local/state/facesketch/recovery-session.json,\n"
                "which the next start offers to restore. Controls: README.md, \"The app\".");
    cmd->add_option("inputs", c->inputs, "SESSION, or MODEL DATASET")->expected(0, 2);
    cmd->add_option("--session-out", c->sessionOut, "Where Ctrl+S saves the session");
    cmd->add_option("--export-out", c->exportOut, "Where Ctrl+E exports the face (.ply or .obj)");
    cmd->add_option("--poses", c->poses,
        "Pose model for pose mode (facesketch train-poses; default: the session's, or with no arguments the built-in one, "
        "trained once into the cache)");
    cmd->add_option("--glb-out", c->glbOut, "Where Ctrl+G exports the timeline as a glTF animation (.glb)");
    cmd->add_option("--mode", c->mode, "Start in this mode: sketch or pose")->capture_default_str();
    cmd->add_option("--time", c->time, "Pose mode: start showing the timeline at this time (s)")->check(CLI::NonNegativeNumber);
    cmd->add_flag("--play", c->play, "Pose mode: start playing the timeline");
    cmd->add_option("--screenshot", c->screenshot, "Write the last frame (with the panels) to this PNG on quitting");
    cmd->add_option("--quit-after-frames", c->quitAfterFrames, "Quit after N frames with data loaded")->check(CLI::NonNegativeNumber);
    cmd->add_option("--bench-frames", c->benchFrames,
           "Orbit for N frames, read one scripted stroke half way, print gui_frame_ms_<V>v (median), gui_frame_p95_ms_<V>v, "
           "gui_stroke_to_frame_ms_<V>v and quit")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option(
        "--size", [c](const CLI::results_t& r) { return std::sscanf(r[0].c_str(), "%dx%d", &c->width, &c->height) == 2; },
        "Window size in pixels, WxH (default 1280x800)");
    cmd->add_option("--msaa", c->samples, "Samples per pixel, 1 or 4")->check(CLI::IsMember({ 1, 4 }))->capture_default_str();
    cmd->add_option("--motion-scale", c->motionScale,
           "While the view moves (orbit, pan, zoom, presets, resizing) draw the face at this fraction of the window's resolution "
           "without MSAA, scaled up; full resolution as soon as the view rests (1: always full)")
        ->check(CLI::Range(0.25, 1.0))
        ->capture_default_str();
    const std::map<std::string, gui::Present> presents { { "auto", gui::Present::Auto }, { "swapchain", gui::Present::Swapchain },
        { "shm", gui::Present::Shm } };
    cmd->add_option("--present", c->present,
           "How frames reach the window: 'swapchain' (Vulkan's), 'shm' (X11 shared memory: for lavapipe, whose swapchain sends "
           "every frame through the X socket) or 'auto' (shm when the device draws on the CPU and the X server can attach it)")
        ->transform(CLI::CheckedTransformer(presents))
        ->default_str("auto");
    cmd->add_option("--autosave-seconds", c->autosaveSeconds, "Autosave interval")->check(CLI::PositiveNumber)->capture_default_str();
    cmd->add_flag("--restore", c->restore, "Restore the recovery file without asking");
    cmd->add_flag("--overlay", c->overlay, "Start with the sketchability overlay on");
    cmd->add_option("--view", c->view, "Start in this view (front, profile, 34 or AZ,EL)")->capture_default_str();
    cmd->add_flag("--print-guides", c->printGuides, "Print where the upper lip and nose profile are in the window (for scripted input)");
    cmd->callback([c] {
        App app(*c);
        app.run();
    });
}

} // namespace facesketch::app

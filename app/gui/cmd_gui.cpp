// `facesketch gui [SESSION | MODEL DATASET]`: the interactive app (issue 14). A window with
// the face, its contours and the strokes drawn on it; strokes are read with the left button and
// applied through the same SessionReplayer as `facesketch sketch`; navigation as in Blender
// (gui/navigation.h); panels for the reading options, the similar training faces, files and
// data. Long work (synthesising and training the built-in data, loading a dataset, the curvature
// pass) runs on a worker thread (gui/worker.h) with a progress bar and Cancel.
//
// Pose mode and the timeline (issue 13) are not here yet: they come with the pose module.

#include "commands.h"
#include "sketch_data.h"

#include "contours/contour_lines.h"
#include "contours/curvature.h"
#include "contours/curvature_cache.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "dataset/synth/synth_dataset.h"
#include "gui/document.h"
#include "gui/navigation.h"
#include "gui/overlay.h"
#include "gui/window.h"
#include "gui/worker.h"
#include "model/head_assembly.h"
#include "model/head_model.h"
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
#include <deque>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace facesketch::app {

namespace {

namespace fs = std::filesystem;

struct GuiCommand {
    std::vector<std::string> inputs;
    std::string sessionOut, exportOut, screenshot;
    int quitAfterFrames = 0;
    int benchFrames = 0;
    int width = 1280, height = 800;
    int samples = 4;
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
    return cache / "builtin-high-v1";
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

std::unique_ptr<Loaded> load(const fs::path& model, const fs::path& dataset, gui::Progress& progress)
{
    auto l = std::make_unique<Loaded>();
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
    void startLoad(fs::path model, fs::path dataset, bool builtIn);
    void startTrain(fs::path dataset, fs::path model);
    void install(std::unique_ptr<Loaded> loaded);
    void pollJob();
    // Input.
    void onMouseButton(int button, int action, int mods, double x, double y);
    void onCursor(double x, double y);
    void onScroll(double steps);
    void onKey(int key, int action, int mods);
    void applyStroke(const sketch::Stroke& stroke);
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
    Mesh displayMesh() const;
    // Panels.
    void panels();
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
    bool trace_ = std::getenv("FACESKETCH_GUI_TRACE") != nullptr; ///< print input events and frame times
};

App::App(const GuiCommand& c)
    : c_(c)
    , window_({ c.width, c.height, "FaceSketch", c.samples })
{
    RenderTargetFormat target;
    target.color = window_.colorFormat();
    target.samples = window_.samples();
    target.renderPass = window_.renderPass();
    scene_ = std::make_unique<SceneRenderer>(window_.device(), target, gpu::framesInFlight);
    if (!c.sessionOut.empty())
        std::snprintf(sessionPath_, sizeof sessionPath_, "%s", c.sessionOut.c_str());
    if (!c.exportOut.empty())
        std::snprintf(exportPath_, sizeof exportPath_, "%s", c.exportOut.c_str());
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
        startLoad(model, dataset, false);
    } else if (c.inputs.size() == 2) {
        startLoad(c.inputs[0], c.inputs[1], false);
    } else if (c.inputs.empty()) {
        const fs::path folder = builtInFolder();
        startLoad(folder / "faces.model", folder / "faces", true);
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

void App::startLoad(fs::path model, fs::path dataset, bool builtIn)
{
    if (job_ && !job_->finished())
        return;
    std::snprintf(modelPath_, sizeof modelPath_, "%s", model.string().c_str());
    std::snprintf(datasetPath_, sizeof datasetPath_, "%s", dataset.string().c_str());
    job_ = std::make_unique<gui::Job>(builtIn ? "preparing the built-in data" : "loading " + dataset.filename().string(),
        [this, model, dataset, builtIn](gui::Progress& p) {
            if (builtIn)
                makeBuiltIn(model.parent_path(), p);
            pending_ = load(model, dataset, p);
        });
}

void App::startTrain(fs::path dataset, fs::path model)
{
    if (job_ && !job_->finished())
        return;
    job_ = std::make_unique<gui::Job>("training a model on " + dataset.filename().string(), [this, model, dataset](gui::Progress& p) {
        const dataset::Dataset ds = dataset::openDataset(dataset);
        const stats::FaceModel m
            = model::trainHeadModel(ds, {}, [&](const std::string& what, double f) { p.report(0.8 * f, "training: " + what); });
        stats::saveFaceModel(m, model);
        pending_ = load(model, dataset, p);
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
    doc_.reset();
    loaded_ = std::move(loaded);
    doc_ = std::make_unique<gui::Document>(*loaded_->replayer, loaded_->model, loaded_->dataset);
    autosave_ = std::make_unique<gui::Autosave>(gui::recoveryFile(), c_.autosaveSeconds, doc_->revision());

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
    haveItems_ = true;

    if (!sessionArg_.empty()) {
        open(sessionArg_);
        sessionArg_.clear();
    } else if (fs::exists(autosave_->file())) {
        try {
            sketch::Session s = sketch::loadSession(autosave_->file());
            const auto [model, dataset] = sketch::sessionInputs(s, autosave_->file());
            if (!s.actions.empty() && fs::equivalent(model, loaded_->model) && fs::equivalent(dataset, loaded_->dataset))
                recovery_ = std::move(s);
            else if (!s.actions.empty())
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
        }
    }
    faceChanged();
    viewDirty_ = true;
    std::cout << "gui: ready, " << loaded_->faceModel->vertexCount() << " vertices, recovery file " << autosave_->file().string()
              << std::endl;
}

void App::say(const std::string& text)
{
    status_ = text;
}

Mesh App::displayMesh() const
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
    if (!nav_)
        return;
    const OrbitView before = nav_->view();
    pointer_.move(x, y, glfwGetTime() * 1000, *nav_);
    if (!sketch::operator==(before, nav_->view()))
        viewDirty_ = true;
}

void App::onScroll(double steps)
{
    if (!nav_ || ImGui::GetIO().WantCaptureMouse)
        return;
    nav_->zoom(steps);
    viewDirty_ = true;
}

void App::onKey(int key, int action, int mods)
{
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
    if (doc_->undo()) {
        say("undone: " + std::to_string(doc_->appliedCount()) + " strokes in effect");
        std::cout << "gui: undone, " << doc_->appliedCount() << " strokes in effect" << std::endl;
        faceChanged();
    }
}

void App::redo()
{
    if (doc_->redo()) {
        say("redone: " + std::to_string(doc_->appliedCount()) + " strokes in effect");
        std::cout << "gui: redone, " << doc_->appliedCount() << " strokes in effect" << std::endl;
        faceChanged();
    }
}

void App::save(const fs::path& path)
{
    try {
        doc_->save(path);
        doc_->markSaved();
        say("saved " + path.string());
        std::cout << "gui: saved " << path.string() << " (" << doc_->appliedCount() << " strokes)" << std::endl;
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
    scene_->updateMesh(faceItem_, displayMesh().V);
    curvature_ = estimateCurvature(face);
    if (!loaded_->data->trainNames.empty()) {
        const std::vector<Mesh> train(loaded_->data->candidateFaces.begin(),
            loaded_->data->candidateFaces.begin() + static_cast<long>(loaded_->data->trainNames.size()));
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
        scene_->setVisible(strokeItems_[i], showStrokes_);
        scene_->setVisible(interpretedItems_[i], showStrokes_);
    }
}

void App::viewChanged()
{
    const Camera camera = orbitCamera(nav_->view());
    if (showContours_) {
        const ContourLines lines = contourLines(doc_->face(), curvature_, camera, contourParams_, loaded_->data->flags);
        std::vector<glm::vec3> all = lines.silhouette;
        all.insert(all.end(), lines.suggestive.begin(), lines.suggestive.end());
        scene_->setLines(contourItem_, all, { { 0.08f, 0.08f, 0.1f, 1 } });
    }
    scene_->setVisible(contourItem_, showContours_);
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
    const Mesh face = doc_->face();
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
    static const char* mappers[] = { "nearest", "heuristic", "hmm (4.8)", "simple" };
    ImGui::Combo("mapper", &mapper_, mappers, 4);
    static const char* surfaces[] = { "face", "front plane", "profile plane", "paper" };
    ImGui::Combo("projection", &surface_, surfaces, 4);
    ImGui::Checkbox("correlation", &correlation_);
    ImGui::SameLine();
    ImGui::Checkbox("symmetry", &symmetry_);
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
    ImGui::Text("%zu strokes%s", doc_->appliedCount(), doc_->revision() != doc_->savedRevision() ? " (unsaved)" : "");
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
    if (!autosave_->lastError().empty())
        ImGui::TextWrapped("autosave failed: %s", autosave_->lastError().c_str());
    ImGui::End();

    ImGui::SetNextWindowPos({ 10 * scale, 560 * scale }, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
    ImGui::Begin("Data");
    ImGui::InputText("model", modelPath_, sizeof modelPath_);
    ImGui::InputText("dataset", datasetPath_, sizeof datasetPath_);
    ImGui::BeginDisabled(job_ != nullptr);
    if (ImGui::Button("load"))
        startLoad(modelPath_, datasetPath_, false);
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

void App::run()
{
    const float background[4] = { 0.93f, 0.93f, 0.94f, 1 };
    std::vector<double> frameMs;
    std::optional<double> strokeToFrameMs;
    std::optional<sketch::Stroke> benchStroke;
    std::optional<double> benchReleasedAt;
    double lastFrameStart = -1;
    bool capture = false, shotTaken = false;
    for (;;) {
        glfwPollEvents();
        pollJob();
        // Quitting draws one more frame when it is to be captured (--screenshot).
        const bool quitting = quit_ || window_.shouldClose();
        if (quitting && (c_.screenshot.empty() || shotTaken || !doc_))
            break;
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_.glfw(), &w, &h);
        const double now = glfwGetTime();

        if (doc_) {
            if (w > 0 && h > 0 && (w != nav_->view().width || h != nav_->view().height)) {
                nav_->resize(w, h);
                viewDirty_ = true;
            }
            // The benchmark: orbit once around the face; half way, one scripted stroke.
            if (c_.benchFrames > 0) {
                const double f = static_cast<double>(readyFrames_) / c_.benchFrames;
                if (readyFrames_ == static_cast<std::uint64_t>(c_.benchFrames / 2)) {
                    nav_->preset('1');
                    sketch::SimulateOptions o;
                    o.imageSize = std::min(w, h);
                    const Mesh& target = loaded_->data->testFaces.empty() ? loaded_->data->candidateFaces[0] : loaded_->data->testFaces[0];
                    const sketch::Simulation sim
                        = sketch::simulateStrokes(target, meanMesh(*loaded_->faceModel), loaded_->data->contours, loaded_->data->flags, o);
                    if (!sim.strokes.empty()) {
                        released_ = sim.strokes.front().stroke;
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
            scene_->setVisible(flashItem_, now < flashUntil_ && std::fmod(now * 8, 2.0) < 1.4);
            autosave_->tick(*doc_, now);
        }

        const bool last = doc_
            && (quitting || (c_.quitAfterFrames > 0 && readyFrames_ + 1 >= static_cast<std::uint64_t>(c_.quitAfterFrames))
                || (c_.benchFrames > 0 && readyFrames_ + 1 >= static_cast<std::uint64_t>(c_.benchFrames)));
        capture = last && !c_.screenshot.empty() && !shotTaken;

        gpu::Frame frame;
        if (!window_.begin(frame, background)) {
            window_.skipFrame();
            if (quitting)
                break;
            if (w == 0 || h == 0)
                glfwWaitEventsTimeout(0.05); // minimised: no frames until restored
            continue;
        }
        panels();
        if (doc_)
            scene_->record(frame.cmd, frame.slot, orbitCamera(nav_->view()), frame.extent);
        window_.end(frame, capture);

        if (doc_) {
            if (lastFrameStart >= 0 && readyFrames_ > 10)
                frameMs.push_back((now - lastFrameStart) * 1000);
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

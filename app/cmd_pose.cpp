// `facesketch pose` and `facesketch animate` (thesis 5.3-5.5, issue 13): replay a session's pose
// strokes onto a face and print the feature points they identified; play its keyframes as PNG
// frames or a glTF 2.0 animation (.glb). Without --face or the session's `face`, the face posed is
// the one the session's shape strokes build (as `facesketch sketch` replays them).

#include "commands.h"
#include "sketch_data.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "io/gltf_export.h"
#include "io/mesh_io.h"
#include "model/head_assembly.h"
#include "pose/animation.h"
#include "pose/pose_file.h"
#include "pose/pose_session.h"
#include "sketch/replay.h"
#include "sketch/session.h"
#include "stats/model_file.h"

#include <iomanip>
#include <iostream>

namespace facesketch::app {

namespace {

/// The face a session shapes with its shape strokes (docs/session-format.md), replayed as
/// `facesketch sketch` and the app replay it (sketch/replay.h SessionReplayer): the session's
/// face model and dataset, every stroke in order (a refused one leaves the face as it was), and
/// the rigid parts (eyes, teeth, tongue) following the skin when the model knows the head, as
/// the app shows it. Pose actions placed between shape strokes pose this final face.
Mesh sketchedFace(const sketch::Session& session, const std::string& sessionFile)
{
    const auto [modelPath, datasetPath] = sketch::sessionInputs(session, sessionFile);
    const stats::FaceModel m = stats::loadFaceModel(modelPath);
    const SketchData d = loadSketchData(datasetPath.string(), &m);
    gpu::ScopedDevice device;
    sketch::SessionReplayer replayer(*device, m, d.candidateFaces, d.flags, d.landmarks, modelPath.string());
    int refused = 0;
    for (const sketch::StrokeAction& a : session.actions)
        refused += replayer.apply(a).kind == sketch::ReplayOutcome::Kind::Refused ? 1 : 0;
    std::cout << "# " << session.actions.size() << " shape strokes replayed (" << replayer.tracking().strokes() << " applied, " << refused
              << " refused): the face to pose\n";
    const Eigen::VectorXd& skin = replayer.tracking().face();
    if (m.head.vertexCount > 0)
        return model::assembleHead(m.head, m.meanFace, skin);
    return { asVertices(skin), m.triangles };
}

/// The face a session poses: --face, else the session's `face`, else the face its shape
/// strokes build, else the pose model's mean face.
Mesh faceToPose(const pose::PoseModel& model, const std::string& faceOption, const sketch::Session& session, const std::string& sessionFile)
{
    if (!faceOption.empty())
        return readMesh(faceOption);
    if (!session.face.empty())
        return readMesh(sketch::sessionPath(sessionFile, session.face));
    if (!session.actions.empty())
        return sketchedFace(session, sessionFile);
    Mesh mean;
    mean.V = asVertices(model.meanNeutral);
    mean.F = model.topology;
    return mean;
}

void printFps(const pose::PoseEditor& editor)
{
    const Vertices posed = editor.featurePointPositions();
    std::cout << std::fixed << std::setprecision(2);
    for (const pose::IdentifiedFp& fp : editor.reading().fps) {
        std::cout << "FP " << fp.name << ": stroke " << fp.stroke << " ("
                  << editor.reading().strokeGroup[static_cast<std::size_t>(fp.stroke)] << ") point " << fp.point
                  << (fp.nudged ? " (endpoint nudged)" : "") << ", drawn (" << fp.position.x() << ", " << fp.position.y() << ", "
                  << fp.position.z() << ") mm, posed (" << posed(fp.fp, 0) << ", " << posed(fp.fp, 1) << ", " << posed(fp.fp, 2)
                  << ") mm\n";
    }
}

struct PoseCommand {
    std::string model, face, session, output;
};

void runPose(const PoseCommand& c)
{
    const sketch::Session session = sketch::loadSession(c.session);
    const pose::PoseModel model = pose::loadPoseModel(c.model);
    const Mesh face = faceToPose(model, c.face, session, c.session);
    pose::PoseEditor editor(model, face);
    int strokes = 0;
    for (const auto& a : session.poseActions)
        strokes += a.kind == sketch::PoseActionKind::Stroke ? 1 : 0;
    Stopwatch clock;
    pose::replayPoseActions(editor, session);
    std::cout << "# " << strokes << " pose strokes, " << editor.keyframes().size() << " keyframes replayed in " << std::setprecision(1)
              << std::fixed << clock.milliseconds() << " ms on " << face.vertexCount() << " vertices\n";
    if (session.poseActions.empty() || editor.reading().fps.empty())
        std::cout << "# no pose strokes since the last clear: the face is neutral\n";
    printFps(editor);
    if (editor.component() >= 0)
        std::cout << "completion component " << editor.component() << "\n";
    writeMesh(c.output, editor.face());
    std::cout << "wrote " << c.output << "\n";
}

struct AnimateCommand {
    std::string session, output, face;
    double fps = 30;
    int size = 512;
};

void runAnimate(const AnimateCommand& c)
{
    const sketch::Session session = sketch::loadSession(c.session);
    if (session.poses.empty())
        fail(c.session, ": poses: missing (animate needs the pose model file, `facesketch train-poses`)");
    const std::filesystem::path modelPath = sketch::sessionPath(c.session, session.poses);
    if (!std::filesystem::is_regular_file(modelPath))
        fail(c.session, ": poses: no pose model file at ", modelPath.string());
    const std::filesystem::path out = c.output;
    const bool glb = out.extension() == ".glb";
    // Refuse before the slow part, as the writers would after it.
    if (!glb && std::filesystem::exists(out) && !(std::filesystem::is_directory(out) && std::filesystem::is_empty(out)))
        fail(out.string(), ": exists and is not an empty folder; frames are written into a new one (or name a .glb file)");
    const pose::PoseModel model = pose::loadPoseModel(modelPath);
    const Mesh face = faceToPose(model, c.face, session, c.session);
    pose::PoseEditor editor(model, face);
    pose::replayPoseActions(editor, session);
    const pose::Timeline timeline = editor.timeline(session.tension);
    const std::vector<double> times = pose::frameTimes(timeline, c.fps);
    Stopwatch clock;
    const GltfAnimation animation = pose::timelineAnimation(model, timeline, face, times);
    std::cout << "# " << timeline.keyframes().size() << " keyframes, " << timeline.begin() << " to " << timeline.end() << " s, "
              << times.size() << " frames at " << c.fps << " fps (tension " << session.tension << "), sampled in " << std::setprecision(1)
              << std::fixed << clock.milliseconds() << " ms\n";
    if (glb) {
        writeGlb(out, animation);
        std::cout << "wrote " << out.string() << " (" << face.vertexCount() << " vertices, " << times.size() << " morph targets)\n";
    } else {
        pose::writeFramePngs(animation, out, c.size);
        std::cout << "wrote " << times.size() << " frames into " << out.string() << "/\n";
    }
}

} // namespace

void addPoseCommand(CLI::App& root)
{
    auto c = std::make_shared<PoseCommand>();
    auto* cmd = root.add_subcommand("pose", "Replay a session's pose strokes onto a face (thesis 5.3, 5.4); print the FPs found");
    cmd->add_option("poses", c->model, "Pose model file (facesketch train-poses)")->required();
    cmd->add_option("--face", c->face,
        "Mesh to pose (OBJ or PLY); default: the session's `face`, else the face its shape strokes build, else the pose model's mean face");
    cmd->add_option("--session", c->session, "Session file with pose strokes (docs/session-format.md)")->required();
    cmd->add_option("-o,--output", c->output, "Posed mesh to write (.ply or .obj)")->required();
    cmd->callback([c] { runPose(*c); });
}

void addAnimateCommand(CLI::App& root)
{
    auto c = std::make_shared<AnimateCommand>();
    auto* cmd = root.add_subcommand("animate", "Play a session's keyframes (thesis 5.5) as PNG frames (OUT/) or glTF 2.0 (OUT.glb)");
    cmd->add_option("session", c->session, "Session file naming its pose model (`poses`) with at least two keyframes")->required();
    cmd->add_option("-o,--output", c->output, "A new folder for frame_0000.png, ... or a .glb file")->required();
    cmd->add_option("--face", c->face,
        "Mesh to pose; default: the session's `face`, else the face its shape strokes build, else the pose model's mean face");
    cmd->add_option("--fps", c->fps, "Frames per second")->capture_default_str()->check(CLI::Range(0.1, 1000.0));
    cmd->add_option("--size", c->size, "PNG frames: pixels square")->capture_default_str()->check(CLI::Range(16, 4096));
    cmd->callback([c] { runAnimate(*c); });
}

} // namespace facesketch::app

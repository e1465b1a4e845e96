// pose_sample DIR: writes a small posing world for the command-line tests (tests/cli/pose.cmake):
// DIR/poses.model (a pose model trained on synthetic poses, tests/pose/pose_fixture.h),
// DIR/face.ply (a face it was not trained on), DIR/session.json (pose strokes along the open
// smile's lips, keyframes at 0, 1 and 2 s with a clear between) and DIR/expected.json: where
// FaceSketch puts a few vertices at some frame times of `animate --fps 10`, for the real glTF
// clients (tools/gltf/three-check.mjs).
#include "core/atomic_file.h"
#include "io/mesh_io.h"
#include "pose/pose_file.h"
#include "pose/pose_session.h"
#include "pose_fixture.h"

#include <iostream>
#include <nlohmann/json.hpp>

using namespace facesketch;

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::cerr << "usage: pose_sample DIR\n";
        return 2;
    }
    try {
        const std::filesystem::path dir = argv[1];
        std::filesystem::create_directories(dir);
        const test::PoseWorld& w = test::poseWorld();
        pose::savePoseModel(w.model, dir / "poses.model");
        writeMesh(dir / "face.ply", w.neutral);
        // The face as the file holds it (float32): what `animate` will pose.
        const Mesh face = readMesh(dir / "face.ply");

        sketch::Session session;
        session.poses = "poses.model";
        session.face = "face.ply";
        auto add = [&](sketch::PoseActionKind kind, double time, const std::string& contour, const std::string& pose) {
            sketch::PoseAction a;
            a.kind = kind;
            a.time = time;
            if (kind == sketch::PoseActionKind::Stroke)
                a.stroke = test::traceStroke(w.pose(pose), w.topology.labels.contours.at(contour), w.front);
            session.poseActions.push_back(a);
        };
        add(sketch::PoseActionKind::Keyframe, 0.0, "", "");
        add(sketch::PoseActionKind::Stroke, 0, "lip_upper_outer", "smile_open");
        add(sketch::PoseActionKind::Stroke, 0, "lip_lower_outer", "smile_open");
        add(sketch::PoseActionKind::Keyframe, 1.0, "", "");
        add(sketch::PoseActionKind::Clear, 0, "", "");
        add(sketch::PoseActionKind::Stroke, 0, "lip_upper_outer", "pucker");
        add(sketch::PoseActionKind::Keyframe, 2.0, "", "");
        sketch::saveSession(dir / "session.json", session);

        // FaceSketch's own frames, as `animate --fps 10` samples them.
        pose::PoseEditor editor(w.model, face);
        pose::replayPoseActions(editor, session);
        const pose::Timeline timeline = editor.timeline(session.tension);
        pose::TimelinePlayer player(w.model, timeline, face);
        nlohmann::json checks = nlohmann::json::array();
        for (double t : { 0.5, 1.0, 1.3 }) {
            const Vertices frame = player.frame(t);
            Eigen::Index moved = 0;
            (frame - face.V).rowwise().norm().maxCoeff(&moved);
            for (Eigen::Index v : { moved, Eigen::Index(0) })
                checks.push_back({ { "time", static_cast<double>(static_cast<float>(t)) }, { "node", "face" }, { "vertex", v },
                    { "position", { frame(v, 0), frame(v, 1), frame(v, 2) } } });
        }
        const std::string text = nlohmann::json { { "toleranceMm", 0.01 }, { "mmPerUnit", 1000.0 }, { "checks", checks } }.dump(1);
        writeFileAtomically(dir / "expected.json", [&](std::ostream& out) { out << text << "\n"; });
    } catch (const std::exception& e) {
        std::cerr << "pose_sample: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

// `facesketch bench pose`: one frame of timeline playback (issue 13; thesis 5.5): the cardinal
// spline sampled at a time, then the face rebuilt from the sampled FP pose by the statistical
// mapping (pose/timeline.h TimelinePlayer). Goal on lavapipe's machine: under 16 ms at 6,000
// vertices (60 fps). The pose model is trained on a small posed synthetic set per resolution.
#include "bench.h"
#include "bench_pose_strokes.h"

#include "core/stopwatch.h"
#include "dataset/synth/synth_dataset.h"
#include "pose/minimal_poses.h"
#include "pose/pose_model.h"
#include "pose/timeline.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <unistd.h>

namespace facesketch::app {

void benchPose(const BenchOptions& options, std::ostream& out)
{
    namespace fs = std::filesystem;
    // FACESKETCH_BENCH_RESOLUTIONS=low,high limits the sets (ultra takes the longest to make).
    std::string list = "low,high,ultra";
    if (const char* env = std::getenv("FACESKETCH_BENCH_RESOLUTIONS"))
        list = env;
    const fs::path dir = fs::temp_directory_path() / ("facesketch-bench-pose-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::vector<pose::MinimalPose> minimal = pose::loadMinimalPoses();
    std::stringstream names(list);
    for (std::string name; std::getline(names, name, ',');) {
        dataset::SynthOptions s;
        s.resolution = dataset::parseResolution(name);
        s.identities = 8; // 6 train, 1 contour, 1 test
        s.poses = true;
        const fs::path folder = dir / name;
        dataset::writeSynthDataset(folder, s);
        const dataset::Dataset ds = dataset::openDataset(folder);
        const pose::PoseSet all = pose::loadPoseSet(ds, { dataset::Role::Train, dataset::Role::Contour, dataset::Role::Test });
        const pose::PoseSet train = pose::selectRole(all, dataset::Role::Train);
        Stopwatch clock;
        pose::PoseModelOptions o;
        o.completion.candidates = { 1, 2, 3 };
        const pose::PoseModel model = pose::trainPoseModel(train, train, minimal, o);
        const int V = model.vertexCount;
        out << "# " << name << ": " << V << " vertices, " << model.fpCount() << " FPs, trained on " << train.identityCount()
            << " identities x " << train.poseCount() << " poses in " << clock.seconds() << " s; mapping q_P "
            << model.mapping.fp.latentDim() << ", q_V " << model.mapping.mesh.latentDim() << ", " << model.mapping.joint.size()
            << " joint components\n";

        // Five keyframes from the test identity's poses, one second apart.
        const pose::PoseSet test = pose::selectRole(all, dataset::Role::Test);
        std::vector<pose::Keyframe> keys;
        for (const char* p : { "neutral", "anger", "smile_open", "surprise", "viseme_O" })
            keys.push_back({ static_cast<double>(keys.size()), test.fpDisplacements.row(test.row(0, test.poseIndex(p))).transpose() });
        const pose::Timeline timeline(keys, 0.0);
        Mesh face;
        face.V = asVertices(Eigen::VectorXd(test.neutrals.row(0).transpose()));
        face.F = model.topology;
        pose::TimelinePlayer player(model, timeline, face);
        Vertices frame;
        player.frame(0.5, frame); // sizes the scratch vectors
        std::vector<double> ms;
        const int frames = std::max(options.repeat, 1) * 10;
        for (int f = 0; f < frames; ++f) {
            const double t = timeline.end() * (f + 0.5) / frames;
            Stopwatch c;
            player.frame(t, frame);
            ms.push_back(c.milliseconds());
        }
        out << "pose_frame_ms_" << V << "v " << median(ms) << " ms\n";
        // Pose strokes to posed face: the test identity's open smile traced from the front.
        Mesh posed = face;
        posed.V = asVertices(Eigen::VectorXd(
            test.neutrals.row(0).transpose() + test.meshDisplacements.row(test.row(0, test.poseIndex("smile_open"))).transpose()));
        benchPoseStrokes(model, face, posed, ds.manifest.contours, options.repeat, out);
        fs::remove_all(folder);
    }
    fs::remove_all(dir);
}

} // namespace facesketch::app

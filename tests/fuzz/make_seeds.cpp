// Writes the seed corpora of tests/fuzz/<target>/ (seed-*) with the program's own writers, so
// every seed is a small valid file: `fuzz_make_seeds tests/fuzz` (tools/fuzz.sh --seeds).
#include "contours/curvature_cache_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "dataset/manifest.h"
#include "io/mesh_io.h"
#include "io/png.h"
#include "pose/pose_file.h"
#include "sketch/session.h"
#include "stats/model_file.h"

#include <cstdio>
#include <fstream>
#include <iterator>

using namespace facesketch;
namespace fs = std::filesystem;

namespace {

std::string readBytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

void writeBytes(const fs::path& path, const std::string& bytes)
{
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

Mesh pyramid()
{
    Mesh m;
    m.V.resize(5, 3);
    m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1;
    m.F.resize(6, 3);
    m.F << 0, 2, 1, 0, 3, 2, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4;
    return m;
}

stats::Ppca ppca(Eigen::Index d, Eigen::Index q, double seed)
{
    stats::Ppca p;
    p.mean = Eigen::VectorXd::LinSpaced(d, seed, seed + 1);
    p.W = Eigen::MatrixXd::Identity(d, q) + 0.1 * Eigen::MatrixXd::Ones(d, q);
    p.sigma2 = 0.5;
    return p;
}

// The smallest model the reader accepts: 4 vertices, one segment; with a one-vertex rigid part
// if `head`.
stats::FaceModel tinyModel(bool head)
{
    stats::FaceModel m;
    m.triangles.resize(2, 3);
    m.triangles << 0, 1, 2, 0, 2, 3;
    m.meanFace = Eigen::VectorXd::LinSpaced(12, -1, 1);
    m.segmentation.core = Eigen::VectorXi::Zero(4);
    m.segmentation.vertices = { { 0, 1, 2, 3 } };
    m.segmentation.weights = { Eigen::VectorXd::Ones(4) };
    stats::SegmentModel sm;
    sm.mixture.priors = Eigen::VectorXd::Ones(1);
    sm.mixture.components = { ppca(12, 1, 0.0) };
    sm.cleanUp = ppca(12, 2, 1.0);
    sm.logLikelihood = -10;
    m.segments = { sm };
    m.correlation.priors = Eigen::VectorXd::Ones(1);
    m.correlation.components = { ppca(2, 1, 2.0) };
    if (head) {
        m.head.vertexCount = 5;
        m.head.skinBegin = 0;
        m.head.topology.resize(1, 3);
        m.head.topology << 0, 1, 4;
        stats::RigidPart eye;
        eye.name = "eye";
        eye.vertices = { 4 };
        eye.mean = Eigen::RowVector3d(0.5, 0.5, 1).eval();
        eye.anchors = { 0, 1 };
        eye.scale = true;
        m.head.parts = { eye };
    } else {
        m.head.topology.resize(0, 3);
    }
    return m;
}

// The smallest pose model training makes (pose/pose_model.h): 4 vertices in two triangles, each
// an FP; 6 identities in 3 poses (neutral, FP 0 and FP 2 moving together two ways).
pose::PoseModel tinyPoseModel()
{
    pose::PoseSet s;
    s.fps = { { "2.1", "4.1", "8.3", "8.4" }, { 0, 1, 2, 3 } };
    s.vertexCount = 4;
    s.topology.resize(2, 3);
    s.topology << 0, 1, 2, 0, 2, 3;
    s.poseNames = { "neutral", "pose_a", "pose_b" };
    const int identities = 6;
    s.fpDisplacements = Eigen::MatrixXd::Zero(3 * identities, 12);
    s.neutrals = Eigen::MatrixXd::Zero(identities, 12);
    for (int i = 0; i < identities; ++i) {
        s.identities.push_back({ "id" + std::to_string(i), dataset::Role::Train });
        s.neutrals.row(i) << 0, 0, 0, 10, 0, 0, 10, 10 + i, 0, 0, 10, 0;
        const double scale = 1.0 + 0.05 * i;
        for (int p = 0; p < 3; ++p) {
            Eigen::RowVectorXd row = 0.01 * Eigen::RowVectorXd::LinSpaced(12, -1.0 + p, 1.0 + i);
            row(0) += scale * p;
            row(7) += (p == 1 ? 5.0 : p == 2 ? -5.0 : 0.0) * scale;
            s.fpDisplacements.row(3 * i + p) = row;
        }
    }
    s.meshDisplacements = s.fpDisplacements;
    pose::PoseModelOptions o;
    o.completion.candidates = { 1, 2 };
    o.completion.latentDims = { 1 };
    o.completion.restarts = 1;
    o.mapping.fpLatentDim = 2;
    o.mapping.meshLatentDim = 2;
    o.mapping.components = 1;
    o.mapping.jointLatentDim = 2;
    o.mapping.restarts = 1;
    return pose::trainPoseModel(s, s, { { "pose_a", { "2.1" } }, { "pose_b", { "2.1" } } }, o);
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: fuzz_make_seeds FOLDER (tests/fuzz)\n");
        return 2;
    }
    const fs::path root = argv[1];
    const fs::path tmp = fs::temp_directory_path() / "facesketch-make-seeds";
    fs::create_directories(tmp);
    try {
        // Meshes: our writers' OBJ and PLY (binary and ASCII), plus hand-written variants the
        // writers never produce (quads, negative and v/vt/vn indices, big-endian, extra properties).
        const Mesh m = pyramid();
        writeObj(tmp / "a.obj", m);
        const std::string obj = readBytes(tmp / "a.obj");
        const std::string objForms = "# forms\nv 0 0 0\nv 1 0 0 1\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                                     "f 1/1/1 2/1/1 3/1/1 4/1/1\nf -4//1 -2//1 -1//1\ng part\nf 1/1 3/1 4/1\n";
        for (const char* target : { "obj", "obj_vertices" }) {
            writeBytes(root / target / "seed-pyramid.obj", obj);
            writeBytes(root / target / "seed-forms.obj", objForms);
        }
        writePly(tmp / "b.ply", m, PlyEncoding::Binary);
        writePly(tmp / "a.ply", m, PlyEncoding::Ascii);
        writeBytes(root / "ply" / "seed-binary.ply", readBytes(tmp / "b.ply"));
        writeBytes(root / "ply" / "seed-ascii.ply", readBytes(tmp / "a.ply"));
        writeBytes(root / "ply" / "seed-extra.ply",
            "ply\nformat ascii 1.0\ncomment extra properties and elements\nelement vertex 4\nproperty double x\nproperty uchar red\n"
            "property double y\nproperty double z\nelement face 1\nproperty list uchar int vertex_index\nproperty float quality\n"
            "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n0 255 0 0\n1 0 0 0\n1 9 1 0\n0 1 1 0\n4 0 1 2 3 "
            "0.5\n0 1\n");
        std::string big = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                          "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
        const float xyz[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
        for (float f : xyz) {
            const auto* b = reinterpret_cast<const char*>(&f);
            big += std::string { b[3], b[2], b[1], b[0] };
        }
        big += std::string("\x03\0\0\0\0\0\0\0\x01\0\0\0\x02", 13);
        writeBytes(root / "ply" / "seed-big-endian.ply", big);

        // The manifest of a dataset of the pyramid.
        dataset::Manifest manifest;
        manifest.vertexCount = 5;
        manifest.topology = m.F;
        manifest.components = { { "skin", 0, 4 }, { "eye_left", 4, 5 } };
        manifest.landmarks = { { "prn", 4 }, { "gn", 0 } };
        manifest.mpeg4 = { { "9.3", 4 } };
        manifest.contours = { { "brow_left", { 0, 1, 2 } } };
        manifest.excluded = { 3 };
        manifest.samples
            = { { "face_0000", "faces/face_0000.ply", dataset::Role::Train }, { "face_0001", "faces/face_0001.ply", dataset::Role::Test } };
        manifest.poses = { { "face_0000", "smile", "poses/face_0000/smile.ply" } };
        dataset::writeManifest(tmp / "manifest.json", manifest);
        writeBytes(root / "manifest" / "seed-pyramid.json", readBytes(tmp / "manifest.json"));

        // ICT-FaceKit JSON: first byte 0 the pose recipes, 1 vertex_indices.json.
        writeBytes(root / "ict_json" / "seed-recipes.json",
            std::string(1, '\0') + "{\"smile\": {\"mouthSmile_L\": 1.0, \"mouthSmile_R\": 0.95}, \"jaw_open\": {\"jawOpen\": 0.6}}");
        std::string landmarks = "\x01{\"idx_to_landmark_verts\": [";
        for (int i = 0; i < 68; ++i)
            landmarks += (i ? ", " : "") + std::to_string(100 * i + 7);
        writeBytes(root / "ict_json" / "seed-landmarks.json", landmarks + "]}");

        // Face models: first byte 0 the payload alone (the harness adds header and checksum),
        // 1 the whole file.
        for (const bool head : { false, true }) {
            stats::saveFaceModel(tinyModel(head), tmp / "m.model");
            const std::string file = readBytes(tmp / "m.model");
            const std::string name = head ? "head" : "face";
            writeBytes(root / "model" / ("seed-" + name + "-payload.bin"), std::string(1, '\0') + file.substr(20, file.size() - 28));
            writeBytes(root / "model" / ("seed-" + name + "-file.bin"), std::string(1, '\1') + file);
            (void)stats::loadFaceModel(tmp / "m.model");
        }

        // A curvature cache of 2 meshes of 3 vertices (first byte 1: the harness fixes the checksum).
        GpuCurvature::PackedShapes packed;
        for (std::uint32_t i = 0; i < 24; ++i)
            packed.shapes.push_back(i * 2654435761u);
        for (std::uint32_t i = 0; i < 6; ++i)
            packed.c23.push_back(i * 40503u);
        const std::string cache = encodeCurvatureCache(0x0123456789abcdefull, 2, 3, packed);
        writeBytes(root / "curvature_cache" / "seed-2x3.bin", std::string(1, '\0') + cache);
        writeBytes(root / "curvature_cache" / "seed-2x3-fixsum.bin", std::string(1, '\1') + cache);

        // A 3 by 2 PNG.
        Image image { 3, 2, {} };
        for (int i = 0; i < 24; ++i)
            image.pixels.push_back(static_cast<std::uint8_t>(37 * i));
        writePng(tmp / "i.png", image);
        writeBytes(root / "png" / "seed-3x2.png", readBytes(tmp / "i.png"));

        // A session of two strokes, one timed.
        sketch::Session session;
        session.model = "faces.model";
        session.dataset = "faces";
        sketch::StrokeAction a;
        a.stroke.points = { { 402.5, 610, 0.0 }, { 431, 618.25, 16.0 } };
        a.stroke.view.width = 1024;
        a.stroke.view.height = 768;
        session.actions.push_back(a);
        sketch::StrokeAction b;
        b.stroke.points = { { 10, 20, std::nullopt }, { 30, 40, std::nullopt }, { 50, 45, std::nullopt } };
        b.stroke.view.kind = Projection::Perspective;
        b.stroke.view.width = 640;
        b.stroke.view.height = 480;
        b.stroke.surface = sketch::Surface::ProfilePlane;
        b.reading.mapper = "nearest";
        b.reading.symmetry = true;
        session.actions.push_back(b);
        writeBytes(root / "session" / "seed-two-strokes.json", sketch::sessionToJson(session));

        // The first stroke with what a stroke records of its reading since 5 December 2026.
        session.actions[0].reading.refinePasses = 2;
        session.actions[0].reading.refineAnchorRings = 2;
        session.actions[0].reading.mapperParams = { { "sigmaDTau", 0.3 }, { "useSkeleton", 1 }, { "maxCandidatesPerPoint", 96 } };

        // A version 3 session with every kind of action: the two shape strokes, pose strokes
        // (primary and alternative), keyframes, moving and deleting one, clearing the pose, and
        // the pose model, face and tension, so the fuzzer starts from every branch of the parser.
        session.poses = "faces.poses";
        session.face = "face.obj";
        session.tension = 0.25;
        auto poseAction = [](sketch::PoseActionKind kind, int afterStrokes) {
            sketch::PoseAction p;
            p.kind = kind;
            p.afterStrokes = afterStrokes;
            return p;
        };
        sketch::PoseAction smile = poseAction(sketch::PoseActionKind::Stroke, 1);
        smile.stroke = a.stroke;
        session.poseActions.push_back(smile);
        sketch::PoseAction key = poseAction(sketch::PoseActionKind::Keyframe, 1);
        key.time = 0.5;
        session.poseActions.push_back(key);
        sketch::PoseAction frown = poseAction(sketch::PoseActionKind::Stroke, 2);
        frown.stroke = b.stroke;
        frown.alternative = true;
        session.poseActions.push_back(frown);
        key.afterStrokes = 2;
        key.time = 1.25;
        session.poseActions.push_back(key);
        sketch::PoseAction move = poseAction(sketch::PoseActionKind::MoveKeyframe, 2);
        move.time = 0.5;
        move.to = 2;
        session.poseActions.push_back(move);
        sketch::PoseAction remove = poseAction(sketch::PoseActionKind::DeleteKeyframe, 2);
        remove.time = 1.25;
        session.poseActions.push_back(remove);
        session.poseActions.push_back(poseAction(sketch::PoseActionKind::Clear, 2));
        writeBytes(root / "session" / "seed-every-action-v3.json", sketch::sessionToJson(session));

        // A pose model: first byte 0 the payload alone (the harness adds header and checksum), 1
        // the whole file.
        pose::savePoseModel(tinyPoseModel(), tmp / "p.poses");
        const std::string poses = readBytes(tmp / "p.poses");
        writeBytes(root / "pose_model" / "seed-tiny-payload.bin", std::string(1, '\0') + poses.substr(20, poses.size() - 28));
        writeBytes(root / "pose_model" / "seed-tiny-file.bin", std::string(1, '\1') + poses);
        (void)pose::loadPoseModel(tmp / "p.poses");

        // A scan's feature points on the harness's 200 mm box (every required point and two
        // optional ones, on four of its faces, so not all in one plane).
        writeBytes(root / "feature_points" / "seed-box.points.json",
            R"({"prn": [0, -20, 100], "sn": [0, -35, 100], "en_l": [15, 10, 100], "en_r": [-15, 10, 100], )"
            R"("ex_l": [100, 12, 60], "ex_r": [-100, 12, 60], "ch_l": [100, -50, 70], "ch_r": [-100, -50, 70], )"
            R"("pg": [0, -100, 80], "g": [0, 40, 101.5], "obs_l": [99, 0, -10]})"
            "\n");
    } catch (const Error& e) {
        std::fprintf(stderr, "fuzz_make_seeds: %s\n", e.what());
        return 1;
    }
    fs::remove_all(tmp);
    return 0;
}

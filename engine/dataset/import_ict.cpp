// ICT Face Model Light import (import_ict.h): reading the model's files, cutting the region,
// drawing identities, making poses from their recipes, writing the dataset. The labelling
// rules are in import_ict_labels.cpp.
//
// Sources: ICT-FaceKit (Li, Ruizhe et al., "Learning Formation of Physically-Based Face
// Attributes", CVPR 2020; https://github.com/ICT-VGL/ICT-FaceKit, README "Regions" for the
// vertex ranges and the 68 landmark indices); the 68-point Multi-PIE / iBUG 300-W landmark
// scheme (Sagonas et al., 300 Faces in-the-Wild Challenge, 2013); landmark definitions of
// thesis Table 3.1 (Farkas, Anthropometry of the Head and Face, 1994); the random draws are
// core/random.h's.
#include "dataset/import_ict.h"

#include "core/error.h"
#include "core/names.h"
#include "core/random.h"
#include "dataset/dataset.h"
#include "dataset/import_ict_labels.h"
#include "dataset/simplify.h"
#include "io/mesh_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

namespace facesketch::dataset {

namespace fs = std::filesystem;

namespace {

constexpr double kCmToMm = 10.0;

// Vertex ranges of the full ICT mesh (ICT-FaceKit README), half-open.
struct Range {
    const char* name;
    int begin, end;
};
constexpr Range kEyeSocketLeft { "eye_socket_left", 13294, 13678 };
constexpr Range kEyeSocketRight { "eye_socket_right", 13678, 14062 };
constexpr Range kEyeLeft { "eye_left", 21451, 23021 };
constexpr Range kEyeRight { "eye_right", 23021, 24591 };
constexpr Range kMouthSocket { "mouth_socket", 11248, 13294 };
// ICT's "gums and tongue" range [14062, 17039) is one connected mesh; its last 428 vertices are
// the tongue body (open at the root, sewn to the floor of the mouth by 25 edges along the
// frenulum). See import_ict.h for how the split was found.
constexpr Range kGums { "gums", 14062, 16611 };
constexpr Range kTongue { "tongue", 16611, 17039 };
constexpr Range kTeethUpper { "teeth_upper", 17039, 19247 };
constexpr Range kTeethLower { "teeth_lower", 19247, 21451 };

// The 68 Multi-PIE landmarks as listed in ICT-FaceKit's README (used if vertex_indices.json is absent).
constexpr int kReadmeLandmarks[68] = { 1225, 1888, 1052, 367, 1719, 1722, 2199, 1447, 966, 3661, 4390, 3927, 3924, 2608, 3272, 4088, 3443,
    268, 493, 1914, 2044, 1401, 3615, 4240, 4114, 2734, 2509, 978, 4527, 4942, 4857, 1140, 2075, 1147, 4269, 3360, 1507, 1542, 1537, 1528,
    1518, 1511, 3742, 3751, 3756, 3721, 3725, 3732, 5708, 5695, 2081, 0, 4275, 6200, 6213, 6346, 6461, 5518, 5957, 5841, 5702, 5711, 5533,
    6216, 6207, 6470, 5517, 5966 };

fs::path modelFolder(const fs::path& path)
{
    if (fs::is_regular_file(path / "FaceXModel" / "generic_neutral_mesh.obj"))
        return path / "FaceXModel";
    if (fs::is_regular_file(path / "generic_neutral_mesh.obj"))
        return path;
    if (!fs::exists(path))
        fail(path.string(), ": does not exist");
    fail(path.string(), ": no FaceXModel/generic_neutral_mesh.obj (not an ICT-FaceKit folder)");
}

} // namespace

const char* ictRegionName(IctRegion region)
{
    switch (region) {
    case IctRegion::NarrowFace:
        return "narrow";
    case IctRegion::Face:
        return "face";
    case IctRegion::HeadNeck:
        return "head";
    }
    return "?";
}

IctRegion parseIctRegion(const std::string& text)
{
    return parseName(text, std::array { IctRegion::NarrowFace, IctRegion::Face, IctRegion::HeadNeck }, ictRegionName, "region");
}

IctModel loadIctModel(const fs::path& path, const IctOptions& options, const std::vector<std::string>& blendshapes)
{
    const fs::path folder = modelFolder(path);
    const fs::path neutralFile = folder / "generic_neutral_mesh.obj";
    const Mesh full = readObj(neutralFile);
    if (full.vertexCount() != kIctVertexCount)
        fail(neutralFile.string(), ": has ", full.vertexCount(), " vertices, the ICT Face Model has ", kIctVertexCount);
    const fs::path landmarkFile = folder / "vertex_indices.json";
    const std::vector<int> pie = fs::exists(landmarkFile) ? readIctLandmarkIndices(landmarkFile)
                                                          : std::vector<int>(std::begin(kReadmeLandmarks), std::end(kReadmeLandmarks));

    // Kept vertex ranges, in output order; skin first.
    const int skinEnd = options.region == IctRegion::NarrowFace ? 6706 : options.region == IctRegion::Face ? 9409 : 11248;
    std::vector<Range> ranges { { "skin", 0, skinEnd } };
    if (options.eyes)
        for (const Range& r : { kEyeSocketLeft, kEyeSocketRight, kEyeLeft, kEyeRight })
            ranges.push_back(r);
    if (options.mouth)
        for (const Range& r : { kMouthSocket, kGums, kTongue, kTeethUpper, kTeethLower })
            ranges.push_back(r);
    std::vector<int> newIndex(kIctVertexCount, -1), kept;
    IctModel model;
    Manifest& m = model.labels;
    for (const Range& r : ranges) {
        m.components.push_back({ r.name, static_cast<int>(kept.size()), static_cast<int>(kept.size()) + r.end - r.begin });
        for (int v = r.begin; v < r.end; ++v) {
            newIndex[static_cast<size_t>(v)] = static_cast<int>(kept.size());
            kept.push_back(v);
        }
        if (std::string(r.name).find("socket") != std::string::npos)
            for (int v = m.components.back().begin; v < m.components.back().end; ++v)
                m.excluded.push_back(v);
    }
    m.vertexCount = static_cast<int>(kept.size());
    std::vector<Eigen::Index> faces;
    for (Eigen::Index f = 0; f < full.triangleCount(); ++f)
        if (newIndex[full.F(f, 0)] >= 0 && newIndex[full.F(f, 1)] >= 0 && newIndex[full.F(f, 2)] >= 0)
            faces.push_back(f);
    m.topology.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (size_t i = 0; i < faces.size(); ++i)
        for (int k = 0; k < 3; ++k)
            m.topology(static_cast<Eigen::Index>(i), k) = newIndex[full.F(faces[i], k)];

    auto restrict = [&](const Vertices& V) {
        Vertices out(static_cast<Eigen::Index>(kept.size()), 3);
        for (size_t i = 0; i < kept.size(); ++i)
            out.row(static_cast<Eigen::Index>(i)) = kCmToMm * V.row(kept[i]);
        return out;
    };
    model.neutral = restrict(full.V);
    const Eigen::RowVectorXd neutralRow = flatten(model.neutral);
    auto delta = [&](const fs::path& file) -> Eigen::RowVectorXd {
        const Vertices V = readObjVertices(file);
        if (V.rows() != kIctVertexCount)
            fail(file.string(), ": has ", V.rows(), " vertices, ", neutralFile.filename().string(), " has ", kIctVertexCount);
        return flatten(restrict(V)) - neutralRow;
    };

    std::vector<fs::path> identityFiles;
    for (int i = 0;; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "identity%03d.obj", i);
        if (!fs::is_regular_file(folder / name))
            break;
        identityFiles.push_back(folder / name);
    }
    if (identityFiles.empty())
        fail(folder.string(), ": no identity000.obj (the identity modes)");
    model.identityModes.resize(3 * m.vertexCount, static_cast<Eigen::Index>(identityFiles.size()));
    for (size_t i = 0; i < identityFiles.size(); ++i)
        model.identityModes.col(static_cast<Eigen::Index>(i)) = delta(identityFiles[i]).transpose();
    for (const std::string& name : blendshapes) {
        const fs::path file = folder / (name + ".obj");
        if (!fs::is_regular_file(file))
            fail(file.string(), ": missing (blendshape '", name, "' used by a pose recipe)");
        model.blendshapes[name] = delta(file);
    }

    std::vector<int> landmarks;
    for (int v : pie) {
        if (newIndex[static_cast<size_t>(v)] < 0 || newIndex[static_cast<size_t>(v)] >= skinEnd)
            fail(folder.string(), ": landmark vertex ", v, " is outside the ", ictRegionName(options.region), " region");
        landmarks.push_back(newIndex[static_cast<size_t>(v)]);
    }
    ict::labelSkin(m, model.neutral, landmarks, skinEnd, ict::robustTip(model.neutral, model.identityModes, landmarks, skinEnd));
    if (options.mouth) {
        ict::labelTongue(m, model.neutral, *m.component("tongue"));
        ict::labelLowerTeeth(m, model.neutral, *m.component("teeth_lower"));
    }
    validateManifest(m, "import ict-facekit");
    return model;
}

Eigen::VectorXd ictCoefficients(std::uint64_t seed, int index, int modes)
{
    Random rng(splitMix64(splitMix64(seed) ^ static_cast<std::uint64_t>(index)), BoxMuller::PlusOne);
    Eigen::VectorXd c(modes);
    for (int i = 0; i < modes; ++i)
        c(i) = rng.normal();
    return c;
}

Vertices ictIdentity(const IctModel& model, const Eigen::VectorXd& coefficients)
{
    if (coefficients.size() != model.identityModes.cols())
        fail("ictIdentity: ", coefficients.size(), " coefficients for ", model.identityModes.cols(), " modes");
    const Eigen::RowVectorXd row = flatten(model.neutral) + (model.identityModes * coefficients).transpose();
    return unflatten(row);
}

Vertices ictPose(const IctModel& model, const Vertices& identity, const std::map<std::string, double>& recipe)
{
    Eigen::RowVectorXd row = flatten(identity);
    for (const auto& [name, weight] : recipe) {
        const auto it = model.blendshapes.find(name);
        if (it == model.blendshapes.end())
            fail("ictPose: blendshape '", name, "' was not loaded");
        row += weight * it->second;
    }
    return unflatten(row);
}

Manifest writeIctDataset(const fs::path& path, const fs::path& output, const IctOptions& options)
{
    if (options.identities < 1)
        fail("import ict-facekit: --identities ", options.identities, ": need at least 1");
    IctPoseRecipes recipes;
    std::vector<std::string> blendshapes;
    if (options.poses) {
        recipes = readIctPoseRecipes(options.recipes);
        std::set<std::string> names;
        for (const auto& [pose, recipe] : recipes)
            for (const auto& [shape, weight] : recipe)
                names.insert(shape);
        blendshapes.assign(names.begin(), names.end());
    }
    const IctModel model = loadIctModel(path, options, blendshapes);

    Manifest m = model.labels;
    Simplification simplification;
    const bool simplify = options.vertices > 0;
    if (simplify) {
        simplification = simplifyTopology(model.neutral, m, options.vertices);
        m = simplifyManifest(m, simplification);
    }
    const std::vector<Role> roles = splitRoles(options.identities);
    const int posed = !options.poses ? 0
        : options.poseIdentities < 0 ? options.identities
                                     : std::min(options.poseIdentities, options.identities);
    for (int i = 0; i < options.identities; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "face_%04d", i);
        m.samples.push_back({ name, fs::path("faces") / (std::string(name) + ".ply"), roles[static_cast<size_t>(i)] });
        if (i < posed)
            for (const auto& [pose, recipe] : recipes)
                m.poses.push_back({ name, pose, fs::path("poses") / name / (pose + ".ply") });
    }

    const int modes = static_cast<int>(model.identityModes.cols());
    writeDataset(output, m, [&](const fs::path& tmp) {
        fs::create_directories(tmp / "faces");
        auto write = [&](const fs::path& file, const Vertices& V) {
            writePly(tmp / file, Mesh { simplify ? keepVertices(V, simplification) : V, m.topology });
        };
        size_t pose = 0;
        for (int i = 0; i < options.identities; ++i) {
            const Vertices identity = ictIdentity(model, ictCoefficients(options.seed, i, modes));
            write(m.samples[static_cast<size_t>(i)].file, identity);
            if (i < posed) {
                fs::create_directories(tmp / "poses" / m.samples[static_cast<size_t>(i)].name);
                for (const auto& [poseName, recipe] : recipes)
                    write(m.poses[pose++].file, ictPose(model, identity, recipe));
            }
        }
    });
    return m;
}

} // namespace facesketch::dataset

#include "entry_points.h"

#include "contours/curvature_cache_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "dataset/import_ict.h"
#include "dataset/manifest.h"
#include "io/mesh_io.h"
#include "io/png.h"
#include "pose/pose_file.h"
#include "registration/feature_points.h"
#include "registration/surface_query.h"
#include "sketch/session.h"
#include "stats/model_file.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace facesketch::fuzz {

namespace fs = std::filesystem;

namespace {

// One scratch folder per process ($TMPDIR, /dev/shm under tools/fuzz.sh), removed at exit.
class Scratch {
public:
    Scratch()
        : folder_(fs::temp_directory_path() / ("facesketch-fuzz-" + std::to_string(getpid())))
    {
        fs::create_directories(folder_);
    }
    ~Scratch()
    {
        std::error_code ignored;
        fs::remove_all(folder_, ignored);
    }
    fs::path write(const std::string& name, const void* data, std::size_t size) const
    {
        const fs::path path = folder_ / name;
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out.flush())
            throw std::runtime_error("fuzz: cannot write " + path.string());
        return path;
    }

private:
    fs::path folder_;
};

fs::path scratch(const std::string& name, const void* data, std::size_t size)
{
    static const Scratch folder;
    return folder.write(name, data, size);
}

// Runs a reader; Error is the refusal every reader must give for bad bytes.
// Runs a reader; Error is the refusal every reader must give for bad bytes. True if it read them.
template <typename F> bool refusedOrRead(F&& read)
{
    try {
        read();
        return true;
    } catch (const Error&) {
        return false;
    }
}

bool obj(const std::uint8_t* data, std::size_t size)
{
    const fs::path file = scratch("input.obj", data, size);
    return refusedOrRead([&] { (void)readMesh(file); });
}

bool objVertices(const std::uint8_t* data, std::size_t size)
{
    const fs::path file = scratch("input.obj", data, size);
    return refusedOrRead([&] { (void)readObjVertices(file); });
}

bool ply(const std::uint8_t* data, std::size_t size)
{
    const fs::path file = scratch("input.ply", data, size);
    return refusedOrRead([&] { (void)readMesh(file); });
}

bool manifest(const std::uint8_t* data, std::size_t size)
{
    const fs::path file = scratch("manifest.json", data, size);
    return refusedOrRead([&] { (void)dataset::readManifest(file); });
}

// First byte even: the pose recipes; odd: vertex_indices.json.
bool ictJson(const std::uint8_t* data, std::size_t size)
{
    if (size == 0)
        return false;
    if (data[0] % 2 == 0) {
        const fs::path file = scratch("ict-poses.json", data + 1, size - 1);
        return refusedOrRead([&] { (void)dataset::readIctPoseRecipes(file); });
    } else {
        const fs::path file = scratch("vertex_indices.json", data + 1, size - 1);
        return refusedOrRead([&] { (void)dataset::readIctLandmarkIndices(file); });
    }
}

// The bytes of a checksummed FaceSketch file (the face and pose model files share one frame:
// magic, version, payload length, payload, FNV-1a of the payload). First byte even: the rest is
// the payload, wrapped in a valid frame so that the fuzzer explores the contents (a random change
// almost never keeps the checksum); odd: the rest is the whole file, as read.
std::string framedFile(const std::uint8_t* data, std::size_t size, const char (&magic)[8], std::uint32_t version)
{
    if (data[0] % 2 == 1)
        return std::string(reinterpret_cast<const char*>(data + 1), size - 1);
    std::string bytes;
    const std::uint64_t length = size - 1;
    const std::uint64_t hash = fnv1a(data + 1, size - 1);
    bytes.append(magic, 8);
    bytes.append(reinterpret_cast<const char*>(&version), sizeof version);
    bytes.append(reinterpret_cast<const char*>(&length), sizeof length);
    bytes.append(reinterpret_cast<const char*>(data + 1), size - 1);
    bytes.append(reinterpret_cast<const char*>(&hash), sizeof hash);
    return bytes;
}

bool model(const std::uint8_t* data, std::size_t size)
{
    if (size == 0)
        return false;
    const std::string bytes = framedFile(data, size, { 'F', 'S', 'K', 'F', 'A', 'C', 'E', '\0' }, stats::kFaceModelVersion);
    const fs::path file = scratch("input.model", bytes.data(), bytes.size());
    return refusedOrRead([&] { (void)stats::loadFaceModel(file); });
}

// The batch asked for is the one the file's header names (when it is a small one), so the
// fuzzer reaches the body; first byte odd: the checksum is fixed up too.
bool curvatureCache(const std::uint8_t* data, std::size_t size)
{
    if (size == 0)
        return false;
    std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
    std::uint64_t key = 1, meshes = 1, vertices = 1;
    if (bytes.size() >= 36) {
        std::memcpy(&key, bytes.data() + 12, 8);
        std::memcpy(&meshes, bytes.data() + 20, 8);
        std::memcpy(&vertices, bytes.data() + 28, 8);
        if (meshes > (1u << 10) || vertices > (1u << 12))
            meshes = vertices = 1;
    }
    if (data[0] % 2 == 1 && bytes.size() >= 44) {
        const std::uint64_t hash = fnv1a(bytes.data(), bytes.size() - 8);
        std::memcpy(bytes.data() + bytes.size() - 8, &hash, 8);
    }
    const fs::path file = scratch("input.curv", bytes.data(), bytes.size());
    GpuCurvature::PackedShapes packed;
    std::string why;
    if (!readCurvatureCacheFile(file, key, meshes, vertices, packed, why))
        return false;
    if (packed.shapes.size() != 4 * meshes * vertices || packed.c23.size() != meshes * vertices)
        throw std::logic_error("curvature cache: restored shapes of the wrong size");
    return true;
}

bool png(const std::uint8_t* data, std::size_t size)
{
    const fs::path file = scratch("input.png", data, size);
    return refusedOrRead([&] { (void)readPng(file); });
}

bool session(const std::uint8_t* data, std::size_t size)
{
    const fs::path file = scratch("session.json", data, size);
    return refusedOrRead([&] { (void)sketch::loadSession(file); });
}

// As `model`, for the pose model file (pose/pose_file.h).
bool poseModel(const std::uint8_t* data, std::size_t size)
{
    if (size == 0)
        return false;
    const std::string bytes = framedFile(data, size, { 'F', 'S', 'K', 'P', 'O', 'S', 'E', '\0' }, pose::kPoseModelVersion);
    const fs::path file = scratch("input.poses", bytes.data(), bytes.size());
    return refusedOrRead([&] { (void)pose::loadPoseModel(file); });
}

// A scan's feature points (`import scans`, DIR/<stem>.points.json), read and then checked against
// a fixed scan as registration checks them: a 200 mm box around the origin.
bool featurePoints(const std::uint8_t* data, std::size_t size)
{
    static const registration::SurfaceQuery scan([] {
        Mesh box;
        box.V.resize(8, 3);
        box.V << -100, -100, -100, 100, -100, -100, 100, 100, -100, -100, 100, -100, -100, -100, 100, 100, -100, 100, 100, 100, 100, -100,
            100, 100;
        box.F.resize(12, 3);
        box.F << 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7;
        return box;
    }());
    const fs::path file = scratch("input.points.json", data, size);
    return refusedOrRead([&] {
        const registration::FeaturePoints points = registration::readFeaturePoints(file);
        registration::validateFeaturePoints(points, scan, "input");
    });
}

} // namespace

const std::vector<Target>& targets()
{
    static const std::vector<Target> all = { { "obj", obj }, { "obj_vertices", objVertices }, { "ply", ply }, { "manifest", manifest },
        { "ict_json", ictJson }, { "model", model }, { "curvature_cache", curvatureCache }, { "png", png }, { "session", session },
        { "pose_model", poseModel }, { "feature_points", featurePoints } };
    return all;
}

const Target& target(const std::string& name)
{
    for (const Target& t : targets())
        if (name == t.name)
            return t;
    throw std::invalid_argument("no fuzz target '" + name + "'");
}

} // namespace facesketch::fuzz

// Mesh-folder import (import_meshes.h).
#include "dataset/import_meshes.h"

#include "core/error.h"
#include "core/random.h"
#include "dataset/dataset.h"
#include "dataset/simplify.h"
#include "io/mesh_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <limits>
#include <set>

namespace facesketch::dataset {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s)
{
    for (char& c : s)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

int vertexField(const fs::path& file, const std::string& field, const nlohmann::json& value)
{
    if (!value.is_number_integer())
        fail(file.string(), ": ", field, ": '", value.dump(), "' is not a vertex index");
    const long v = value.get<long>();
    if (v < 0 || v > std::numeric_limits<int>::max())
        fail(file.string(), ": ", field, ": vertex ", v, " is negative or too large");
    return static_cast<int>(v);
}

// Reads the labels file into `m` (landmarks, mpeg4, contours, components, excluded); returns the scale to mm.
double readLabels(const fs::path& file, Manifest& m)
{
    std::ifstream in(file);
    if (!in)
        fail(file.string(), ": cannot open");
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        fail(file.string(), ": not valid JSON: ", e.what());
    }
    if (!doc.is_object())
        fail(file.string(), ": expected a JSON object");
    static const std::set<std::string> known { "units", "landmarks", "mpeg4", "contours", "components", "excluded" };
    for (const auto& [key, value] : doc.items())
        if (!known.count(key))
            fail(file.string(), ": ", key, ": unknown key (known: units, landmarks, mpeg4, contours, components, excluded)");
    double scale = 1;
    if (doc.contains("units")) {
        const auto& u = doc["units"];
        if (!u.is_string())
            fail(file.string(), ": units: ", u.dump(), " is not a string (\"mm\", \"cm\" or \"m\")");
        scale = millimetresPer(u.get<std::string>(), file.string());
    }
    for (const char* key : { "landmarks", "mpeg4" })
        if (doc.contains(key)) {
            if (!doc[key].is_object())
                fail(file.string(), ": ", key, ": expected an object {name: vertex}");
            auto& target = std::string(key) == "landmarks" ? m.landmarks : m.mpeg4;
            for (const auto& [name, v] : doc[key].items())
                target[name] = vertexField(file, cat(key, ".", name), v);
        }
    if (doc.contains("contours")) {
        if (!doc["contours"].is_object())
            fail(file.string(), ": contours: expected an object {name: [v0, v1, ...]}");
        for (const auto& [name, path] : doc["contours"].items()) {
            if (!path.is_array())
                fail(file.string(), ": contours.", name, ": expected an array of vertices");
            for (size_t i = 0; i < path.size(); ++i)
                m.contours[name].push_back(vertexField(file, cat("contours.", name, "[", i, "]"), path[i]));
        }
    }
    if (doc.contains("components")) {
        if (!doc["components"].is_object())
            fail(file.string(), ": components: expected an object {name: [begin, end]}");
        m.components.clear();
        for (const auto& [name, range] : doc["components"].items()) {
            if (!range.is_array() || range.size() != 2)
                fail(file.string(), ": components.", name, ": expected [begin, end]");
            m.components.push_back({ name, vertexField(file, "components." + name + "[0]", range[0]),
                vertexField(file, "components." + name + "[1]", range[1]) });
        }
    }
    if (doc.contains("excluded")) {
        if (!doc["excluded"].is_array())
            fail(file.string(), ": excluded: expected an array of vertices");
        for (size_t i = 0; i < doc["excluded"].size(); ++i)
            m.excluded.push_back(vertexField(file, cat("excluded[", i, "]"), doc["excluded"][i]));
    }
    return scale;
}

} // namespace

std::vector<Role> shuffledRoles(int count, std::uint64_t seed)
{
    const std::vector<Role> roles = splitRoles(count);
    const std::vector<int> order = Random(seed).permutation(count);
    std::vector<Role> out(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i)
        out[static_cast<size_t>(order[static_cast<size_t>(i)])] = roles[static_cast<size_t>(i)];
    return out;
}

Manifest importMeshes(const fs::path& folder, const fs::path& output, const MeshImportOptions& options)
{
    if (!fs::is_directory(folder))
        fail(folder.string(), ": ", fs::exists(folder) ? "not a folder" : "does not exist");
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string ext = lower(entry.path().extension().string());
        if (entry.is_regular_file() && (ext == ".obj" || ext == ".ply"))
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty())
        fail(folder.string(), ": no .obj or .ply meshes");

    Manifest m;
    const fs::path labels = !options.labels.empty() ? options.labels : folder / "landmarks.json";
    double scale = 1;
    if (!options.labels.empty() || fs::exists(labels))
        scale = readLabels(labels, m);

    std::vector<Vertices> meshes;
    for (const fs::path& file : files) {
        Mesh mesh = readMesh(file);
        validateMesh(mesh, file.string());
        if (meshes.empty()) {
            m.vertexCount = static_cast<int>(mesh.vertexCount());
            m.topology = mesh.F;
        } else {
            if (mesh.vertexCount() != m.vertexCount)
                fail(file.string(), ": has ", mesh.vertexCount(), " vertices, ", files.front().filename().string(), " has ", m.vertexCount,
                    " (all meshes must share one topology)");
            if (mesh.triangleCount() != m.topology.rows())
                fail(file.string(), ": has ", mesh.triangleCount(), " triangles, ", files.front().filename().string(), " has ",
                    m.topology.rows(), " (all meshes must share one topology)");
            for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f)
                if (mesh.F.row(f) != m.topology.row(f))
                    fail(file.string(), ": triangle ", f, " (", mesh.F(f, 0), ", ", mesh.F(f, 1), ", ", mesh.F(f, 2), ") differs from ",
                        files.front().filename().string(), "'s (", m.topology(f, 0), ", ", m.topology(f, 1), ", ", m.topology(f, 2), ")");
        }
        meshes.push_back(scale * mesh.V);
    }
    if (m.components.empty())
        m.components.push_back({ "skin", 0, m.vertexCount });
    validateManifest(m, labels.string());

    Simplification simplification;
    const bool simplify = options.vertices > 0;
    if (simplify) {
        Vertices mean = Vertices::Zero(m.vertexCount, 3);
        for (const Vertices& V : meshes)
            mean += V;
        mean /= static_cast<double>(meshes.size());
        simplification = simplifyTopology(mean, m, options.vertices);
        m = simplifyManifest(m, simplification);
    }
    const std::vector<Role> roles = shuffledRoles(static_cast<int>(files.size()), options.seed);
    for (size_t i = 0; i < files.size(); ++i) {
        const std::string stem = files[i].stem().string();
        m.samples.push_back({ stem, fs::path("faces") / (stem + ".ply"), roles[i] });
    }
    writeDataset(output, m, [&](const fs::path& tmp) {
        fs::create_directories(tmp / "faces");
        for (size_t i = 0; i < files.size(); ++i)
            writePly(tmp / m.samples[i].file, Mesh { simplify ? keepVertices(meshes[i], simplification) : meshes[i], m.topology });
    });
    return m;
}

} // namespace facesketch::dataset

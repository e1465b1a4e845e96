// Wavefront OBJ through tinyobjloader, with a line-level check of our own first: tinyobjloader
// reads a missing coordinate as 0 and an out-of-range index as whatever it finds, and reports
// no line numbers, while our users need "file:line: what" for every bad statement.
// readObjVertices is a reader of its own: `v` lines only, parsed in double precision
// (tinyobjloader's are float), fast enough for the ICT model's 100+ files of 26,719 vertices.

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/limits.h"
#include "io/mesh_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

namespace facesketch {

namespace {

constexpr size_t kMaxObjFaceCorners = 255;

std::vector<std::string> tokens(const std::string& line)
{
    std::istringstream in(line);
    std::vector<std::string> out;
    for (std::string t; in >> t;)
        out.push_back(t);
    return out;
}

// Checks every `v` and `f` statement; returns the vertex count. `where(n)` is "FILE:n".
long checkObjLines(const std::filesystem::path& path)
{
    limits::checkFileSize(path, limits::kMaxMeshFileBytes, "a mesh file");
    std::ifstream in(path);
    if (!in)
        fail(path.string(), ": cannot open");
    long vertices = 0, line = 0;
    std::string text;
    while (std::getline(in, text)) {
        ++line;
        if (!text.empty() && text.back() == '\r')
            text.pop_back();
        const auto t = tokens(text);
        if (t.empty())
            continue;
        auto where = [&] { return cat(path.string(), ":", line, ": "); };
        if (t[0] == "v") {
            if (t.size() < 4)
                fail(where(), "vertex has ", t.size() - 1, " coordinates, expected 3: '", text, "'");
            for (int c = 1; c <= 3; ++c) {
                char* end = nullptr;
                const double x = std::strtod(t[c].c_str(), &end);
                if (*end != '\0')
                    fail(where(), "vertex coordinate '", t[c], "' is not a number");
                if (!std::isfinite(x))
                    fail(where(), "vertex coordinate ", "xyz"[c - 1], " is ", t[c]);
            }
            if (++vertices > limits::kMaxMeshVertices)
                fail(where(), "more than the ", limits::kMaxMeshVertices, " vertices a mesh may have (docs/limits.md)");
        } else if (t[0] == "f") {
            if (t.size() < 4)
                fail(where(), "face has ", t.size() - 1, " vertices, at least 3 needed: '", text, "'");
            // tinyobjloader counts a face's corners in an unsigned char.
            if (t.size() - 1 > kMaxObjFaceCorners)
                fail(where(), "face has ", t.size() - 1, " vertices, at most ", kMaxObjFaceCorners, " are supported");
            std::vector<long> seen;
            for (size_t c = 1; c < t.size(); ++c) {
                const std::string index = t[c].substr(0, t[c].find('/'));
                long value = 0;
                const auto [ptr, ec] = std::from_chars(index.data(), index.data() + index.size(), value);
                if (ec != std::errc() || ptr != index.data() + index.size())
                    fail(where(), "face vertex '", t[c], "' is not an index");
                const long resolved = value < 0 ? vertices + value : value - 1;
                if (value == 0 || resolved < 0 || resolved >= vertices)
                    fail(where(), "face index ", value, " refers to no vertex (", vertices, " defined so far)");
                if (std::find(seen.begin(), seen.end(), resolved) != seen.end())
                    fail(where(), "face repeats vertex ", value);
                seen.push_back(resolved);
            }
        }
    }
    if (in.bad())
        fail(path.string(), ": read error");
    return vertices;
}

} // namespace

Mesh readObj(const std::filesystem::path& path)
{
    const long vertexCount = checkObjLines(path);

    tinyobj::ObjReaderConfig config;
    config.triangulate = false; // we fan-triangulate, keeping one face per `f` line
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path.string(), config))
        fail(path.string(), ": ", reader.Error());
    const auto& attrib = reader.GetAttrib();
    if (static_cast<long>(attrib.vertices.size()) != 3 * vertexCount)
        fail(path.string(), ": read ", attrib.vertices.size() / 3, " vertices but the file has ", vertexCount, " `v` lines");

    Mesh mesh;
    mesh.V.resize(vertexCount, 3);
    for (long v = 0; v < vertexCount; ++v)
        for (int c = 0; c < 3; ++c)
            mesh.V(v, c) = attrib.vertices[3 * v + c];

    std::vector<std::array<std::int32_t, 3>> triangles;
    for (const auto& shape : reader.GetShapes()) {
        size_t offset = 0;
        for (const unsigned char n : shape.mesh.num_face_vertices) {
            for (unsigned k = 1; k + 1 < n; ++k)
                triangles.push_back({ shape.mesh.indices[offset].vertex_index, shape.mesh.indices[offset + k].vertex_index,
                    shape.mesh.indices[offset + k + 1].vertex_index });
            offset += n;
        }
        if (offset != shape.mesh.indices.size())
            fail(path.string(), ": tinyobjloader read ", shape.mesh.indices.size(), " face corners but counted ", offset);
    }
    if (static_cast<std::int64_t>(triangles.size()) > limits::kMaxMeshTriangles)
        fail(path.string(), ": ", triangles.size(), " triangles, more than the ", limits::kMaxMeshTriangles,
            " a mesh may have (docs/limits.md)");
    mesh.F.resize(static_cast<Eigen::Index>(triangles.size()), 3);
    for (size_t t = 0; t < triangles.size(); ++t)
        mesh.F.row(static_cast<Eigen::Index>(t)) << triangles[t][0], triangles[t][1], triangles[t][2];
    validateMesh(mesh, path.string());
    return mesh;
}

Vertices readObjVertices(const std::filesystem::path& path)
{
    const std::string text = limits::readFileLimited(path, limits::kMaxMeshFileBytes, "a mesh file");
    std::vector<double> xyz;
    long line = 0;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos)
            end = text.size();
        ++line;
        const char* p = text.data() + pos;
        const char* e = text.data() + end;
        pos = end + 1;
        if (e - p < 2 || p[0] != 'v' || (p[1] != ' ' && p[1] != '\t'))
            continue;
        const std::string_view lineText(p, static_cast<size_t>(e - p));
        p += 2;
        for (int c = 0; c < 3; ++c) {
            while (p < e && (*p == ' ' || *p == '\t'))
                ++p;
            double value = 0;
            const auto [next, ec] = std::from_chars(p, e, value);
            if (ec != std::errc() || (next < e && *next != ' ' && *next != '\t' && *next != '\r'))
                fail(path.string(), ":", line, ": vertex coordinate ", "xyz"[c], " is missing or not a number: '", lineText, "'");
            if (!std::isfinite(value))
                fail(path.string(), ":", line, ": vertex coordinate ", "xyz"[c], " is ", value);
            xyz.push_back(value);
            p = next;
        }
        if (static_cast<std::int64_t>(xyz.size() / 3) > limits::kMaxMeshVertices)
            fail(path.string(), ":", line, ": more than the ", limits::kMaxMeshVertices, " vertices a mesh may have (docs/limits.md)");
    }
    Vertices V(static_cast<Eigen::Index>(xyz.size() / 3), 3);
    std::copy(xyz.begin(), xyz.end(), V.data());
    return V;
}

void writeObj(const std::filesystem::path& path, const Mesh& mesh)
{
    validateMesh(mesh, path.string());
    writeFileAtomically(path, [&](std::ostream& out) {
        out.precision(9);
        out << "# FaceSketch mesh: " << mesh.V.rows() << " vertices, " << mesh.F.rows() << " triangles\n";
        for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
            out << "v " << mesh.V(v, 0) << ' ' << mesh.V(v, 1) << ' ' << mesh.V(v, 2) << '\n';
        for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
            out << "f " << mesh.F(t, 0) + 1 << ' ' << mesh.F(t, 1) + 1 << ' ' << mesh.F(t, 2) + 1 << '\n';
    });
}

} // namespace facesketch

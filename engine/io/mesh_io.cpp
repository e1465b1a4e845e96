#include "io/mesh_io.h"

#include "core/error.h"

#include <algorithm>
#include <cctype>

namespace facesketch {

namespace {
std::string lowerExtension(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}
} // namespace

Mesh readMesh(const std::filesystem::path& path)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".obj")
        return readObj(path);
    if (ext == ".ply")
        return readPly(path);
    fail(path.string(), ": unknown mesh format '", ext, "' (expected .obj or .ply)");
}

void writeMesh(const std::filesystem::path& path, const Mesh& mesh)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".obj")
        return writeObj(path, mesh);
    if (ext == ".ply")
        return writePly(path, mesh);
    fail(path.string(), ": unknown mesh format '", ext, "' (expected .obj or .ply)");
}

} // namespace facesketch

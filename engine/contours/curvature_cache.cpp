#include "contours/curvature_cache.h"

#include "contours/curvature_cache_file.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/stopwatch.h"
#include "shaders/curvature_comp.h"
#include "shaders/curvature_derivative_comp.h"
#include "shaders/normals_comp.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

namespace facesketch {

std::filesystem::path defaultCacheFolder()
{
    if (const char* dir = std::getenv("FACESKETCH_CACHE_DIR"); dir && *dir)
        return dir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return std::filesystem::path(xdg) / "facesketch";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "facesketch";
    return {};
}

std::uint64_t curvatureCacheKey(const Triangles& F, const std::vector<float>& positions)
{
    std::uint64_t key = fnv1a(&kCurvatureCacheVersion, sizeof kCurvatureCacheVersion);
    const std::uint64_t rows = static_cast<std::uint64_t>(F.rows());
    key = fnv1a(&rows, sizeof rows, key);
    key = fnv1a(F.data(), static_cast<std::size_t>(F.size()) * sizeof(F(0, 0)), key);
    key = fnv1a(positions.data(), positions.size() * sizeof(float), key);
    key = fnv1a(normals_comp, sizeof normals_comp, key);
    key = fnv1a(curvature_comp, sizeof curvature_comp, key);
    return fnv1a(curvature_derivative_comp, sizeof curvature_derivative_comp, key);
}

CachedCurvature runCurvatureCached(
    GpuCurvature& curvature, const Triangles& F, const std::vector<float>& positions, const std::filesystem::path& folder)
{
    CachedCurvature out;
    if (folder.empty()) {
        out.milliseconds = curvature.run();
        return out;
    }
    const std::uint64_t key = curvatureCacheKey(F, positions);
    const std::uint64_t meshes = curvature.meshCount(), vertices = static_cast<std::uint64_t>(curvature.vertexCount());
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.curv", static_cast<unsigned long long>(key));
    out.file = folder / name;

    std::error_code ec;
    if (std::filesystem::is_regular_file(out.file, ec)) {
        Stopwatch clock;
        GpuCurvature::PackedShapes packed;
        std::string why;
        if (readCurvatureCacheFile(out.file, key, meshes, vertices, packed, why)) {
            curvature.uploadShapes(packed);
            out.restored = true;
            out.milliseconds = clock.milliseconds();
            return out;
        }
        out.note = out.file.string() + ": " + why + "; computed again and replaced";
    }

    out.milliseconds = curvature.run();
    try {
        std::filesystem::create_directories(folder);
        const std::string bytes = encodeCurvatureCache(key, meshes, vertices, curvature.downloadShapes());
        writeFileAtomically(out.file, [&](std::ostream& os) { os.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
    } catch (const std::exception& e) {
        out.note = std::string("curvature cache not written: ") + e.what();
        out.file.clear();
    }
    return out;
}

} // namespace facesketch

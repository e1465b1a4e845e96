#include "contours/curvature_cache.h"

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

namespace {

constexpr char kMagic[8] = { 'F', 'S', 'K', 'C', 'U', 'R', 'V', '\0' };
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeader = 8 + 4 + 3 * 8;

template <typename T> void put(std::string& out, const T& value)
{
    out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

template <typename T> T get(const std::string& in, std::size_t offset)
{
    T value;
    std::memcpy(&value, in.data() + offset, sizeof value);
    return value;
}

// The whole file's bytes for a batch.
std::string encode(std::uint64_t key, std::uint64_t meshes, std::uint64_t vertices, const GpuCurvature::PackedShapes& p)
{
    std::string out(kMagic, sizeof kMagic);
    put(out, kVersion);
    put(out, key);
    put(out, meshes);
    put(out, vertices);
    out.append(reinterpret_cast<const char*>(p.shapes.data()), p.shapes.size() * 4);
    out.append(reinterpret_cast<const char*>(p.c23.data()), p.c23.size() * 4);
    put(out, fnv1a(out.data(), out.size()));
    return out;
}

// The shapes in `bytes` if they are a whole file for this batch; otherwise why not.
bool decode(const std::string& bytes, std::uint64_t key, std::uint64_t meshes, std::uint64_t vertices, GpuCurvature::PackedShapes& p,
    std::string& why)
{
    const std::uint64_t n = meshes * vertices;
    if (bytes.size() < kHeader || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        return why = "not a curvature cache file", false;
    if (get<std::uint32_t>(bytes, 8) != kVersion)
        return why = "version " + std::to_string(get<std::uint32_t>(bytes, 8)) + ", expected " + std::to_string(kVersion), false;
    if (get<std::uint64_t>(bytes, 12) != key || get<std::uint64_t>(bytes, 20) != meshes || get<std::uint64_t>(bytes, 28) != vertices)
        return why = "made for other data", false;
    if (bytes.size() != kHeader + 20 * n + 8)
        return why = "truncated (" + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(kHeader + 20 * n + 8) + ")", false;
    if (fnv1a(bytes.data(), bytes.size() - 8) != get<std::uint64_t>(bytes, bytes.size() - 8))
        return why = "checksum mismatch (corrupt)", false;
    p.shapes.resize(4 * n);
    p.c23.resize(n);
    std::memcpy(p.shapes.data(), bytes.data() + kHeader, 16 * n);
    std::memcpy(p.c23.data(), bytes.data() + kHeader + 16 * n, 4 * n);
    return true;
}

} // namespace

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
    std::uint64_t key = fnv1a(&kVersion, sizeof kVersion);
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
        std::ifstream in(out.file, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        GpuCurvature::PackedShapes packed;
        std::string why;
        if (in.good() || in.eof()) {
            if (decode(bytes, key, meshes, vertices, packed, why)) {
                curvature.uploadShapes(packed);
                out.restored = true;
                out.milliseconds = clock.milliseconds();
                return out;
            }
        } else {
            why = "cannot be read";
        }
        out.note = out.file.string() + ": " + why + "; computed again and replaced";
    }

    out.milliseconds = curvature.run();
    try {
        std::filesystem::create_directories(folder);
        const std::string bytes = encode(key, meshes, vertices, curvature.downloadShapes());
        writeFileAtomically(out.file, [&](std::ostream& os) { os.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
    } catch (const std::exception& e) {
        out.note = std::string("curvature cache not written: ") + e.what();
        out.file.clear();
    }
    return out;
}

} // namespace facesketch

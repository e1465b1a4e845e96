#include "contours/curvature_cache_file.h"

#include "core/hash.h"

#include <algorithm>
#include <cstring>
#include <fstream>

namespace facesketch {

namespace {

constexpr char kMagic[8] = { 'F', 'S', 'K', 'C', 'U', 'R', 'V', '\0' };
constexpr std::uint32_t kVersion = kCurvatureCacheVersion;
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

} // namespace

std::string encodeCurvatureCache(std::uint64_t key, std::uint64_t meshes, std::uint64_t vertices, const GpuCurvature::PackedShapes& p)
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

bool readCurvatureCacheFile(const std::filesystem::path& file, std::uint64_t key, std::uint64_t meshes, std::uint64_t vertices,
    GpuCurvature::PackedShapes& packed, std::string& why)
{
    const std::uint64_t n = meshes * vertices;
    const std::uint64_t expected = kHeader + 20 * n + 8;
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(file, ec);
    if (ec)
        return why = "cannot be read (" + ec.message() + ")", false;
    // Only a file of exactly the expected size can hold this batch: read at most that many
    // bytes (a header, if the size is wrong, to say why).
    std::ifstream in(file, std::ios::binary);
    std::string bytes(static_cast<std::size_t>(size == expected ? expected : std::min<std::uint64_t>(size, kHeader)), '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!in || static_cast<std::size_t>(in.gcount()) != bytes.size())
        return why = "cannot be read", false;
    if (bytes.size() < kHeader || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        return why = "not a curvature cache file", false;
    if (get<std::uint32_t>(bytes, 8) != kVersion)
        return why = "version " + std::to_string(get<std::uint32_t>(bytes, 8)) + ", expected " + std::to_string(kVersion), false;
    if (get<std::uint64_t>(bytes, 12) != key || get<std::uint64_t>(bytes, 20) != meshes || get<std::uint64_t>(bytes, 28) != vertices)
        return why = "made for other data", false;
    if (size != expected)
        return why = "truncated (" + std::to_string(size) + " bytes, expected " + std::to_string(expected) + ")", false;
    if (fnv1a(bytes.data(), bytes.size() - 8) != get<std::uint64_t>(bytes, bytes.size() - 8))
        return why = "checksum mismatch (corrupt)", false;
    packed.shapes.resize(4 * n);
    packed.c23.resize(n);
    if (n > 0) { // an empty vector's data() may be null, which memcpy may not be given
        std::memcpy(packed.shapes.data(), bytes.data() + kHeader, 16 * n);
        std::memcpy(packed.c23.data(), bytes.data() + kHeader + 16 * n, 4 * n);
    }
    return true;
}

} // namespace facesketch

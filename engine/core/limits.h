#pragma once
// The limits every reader of outside bytes enforces (docs/limits.md). A file from another tool
// or another person is never trusted to say how much memory it needs: a header that declares
// 4 billion vertices, a count that overflows when multiplied, a JSON document nested a million
// deep or a 10 MB name is refused with an Error naming the file, the field and the limit
// before anything of that size is allocated. The limits sit far above any real FaceSketch data
// (the ICT Face Model has 26,719 vertices; a 250-face dataset manifest is under 1 MB).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace facesketch::limits {

/// Vertices of one mesh (OBJ, PLY, a manifest's vertex_count): 2^26, about 67 million.
inline constexpr std::int64_t kMaxMeshVertices = std::int64_t(1) << 26;
/// Triangles of one mesh, after fan triangulation: 2^27.
inline constexpr std::int64_t kMaxMeshTriangles = std::int64_t(1) << 27;
/// Corners of one polygon (a PLY face list, an OBJ `f` line).
inline constexpr std::int64_t kMaxPolygonCorners = 1 << 16;
/// Instances of any one PLY element, whatever its name (also the ones the reader skips).
inline constexpr std::int64_t kMaxPlyElementCount = std::int64_t(1) << 28;
/// Bytes of a mesh file (OBJ, PLY): 4 GiB.
inline constexpr std::uint64_t kMaxMeshFileBytes = std::uint64_t(1) << 32;
/// Bytes of a JSON file FaceSketch reads (dataset manifest, session, ICT-FaceKit JSON,
/// pose recipes): 256 MiB.
inline constexpr std::uint64_t kMaxJsonFileBytes = std::uint64_t(1) << 28;
/// Nesting depth of arrays and objects in a JSON document (ours nest at most 6 deep).
inline constexpr int kMaxJsonDepth = 64;
/// Bytes of one JSON string (names, file names, keys), as written in the file: 64 KiB.
inline constexpr std::uint64_t kMaxJsonStringBytes = std::uint64_t(1) << 16;
/// Bytes of a face model file: 16 GiB (a model at 6,000 vertices is tens of megabytes).
inline constexpr std::uint64_t kMaxModelFileBytes = std::uint64_t(1) << 34;
/// Bytes of a PNG file read: 256 MiB.
inline constexpr std::uint64_t kMaxImageFileBytes = std::uint64_t(1) << 28;
/// Pixels of a PNG read: 2^26 (8192 by 8192), 256 MiB as RGBA.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t(1) << 26;

/// The size of the regular file at path in bytes. Throws Error "<path>: cannot open" if it is
/// not a readable regular file, and "<path>: <bytes> bytes, more than the <limit> bytes <what>
/// may have (docs/limits.md)" if it is larger than maxBytes.
std::uint64_t checkFileSize(const std::filesystem::path& path, std::uint64_t maxBytes, const char* what);

/// The whole file as bytes after checkFileSize(path, maxBytes, what). Throws Error naming the
/// path on a read error.
std::string readFileLimited(const std::filesystem::path& path, std::uint64_t maxBytes, const char* what);

/// Scans a JSON text (without parsing it) and throws Error "<where>: byte N: ..." if arrays and
/// objects nest deeper than kMaxJsonDepth or a string is longer than kMaxJsonStringBytes, so a
/// hostile document is refused before the parser builds it (nlohmann's parser and dump() would
/// use memory and stack in proportion). Malformed JSON passes through to the parser's message.
void checkJsonLimits(std::string_view text, const std::string& where);

} // namespace facesketch::limits

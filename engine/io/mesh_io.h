#pragma once
// Reading and writing triangle meshes: Wavefront OBJ (through tinyobjloader) and Stanford PLY
// (ASCII, binary little- and big-endian; our own reader, as Debian packages no PLY library).
// Polygons are fan-triangulated. Only positions and faces are kept: FaceSketch's datasets
// carry everything else in their manifest.
//
// Every reader validates what it read (counts, indices, finite coordinates) and throws
// facesketch::Error with "FILE:LINE: what is wrong" (binary PLY: "FILE: vertex N" or
// "FILE: byte N"). Every writer is atomic (core/atomic_file.h).

#include "core/mesh.h"

#include <filesystem>

namespace facesketch {

enum class PlyEncoding { Binary, Ascii };

/// Reads an .obj or .ply file, chosen by extension (case-insensitive).
Mesh readMesh(const std::filesystem::path& path);
/// Writes .obj or .ply by extension; PLY is binary little-endian with float32 positions.
void writeMesh(const std::filesystem::path& path, const Mesh& mesh);

/// OBJ: `v x y z` lines (extra w or colour columns ignored), `f` lines with 1-based or negative
/// indices in any of the v, v/vt, v//vn, v/vt/vn forms.
Mesh readObj(const std::filesystem::path& path);
/// The `v` lines of an OBJ file only, as #V by 3 in file units, parsed in double precision
/// (readObj keeps tinyobjloader's float precision); every other statement is skipped, so files
/// cut down to their `v` lines are read too. Throws Error "FILE:LINE: vertex coordinate y is
/// missing or not a number: '<line>'" (or "... is nan") on a bad `v` line.
Vertices readObjVertices(const std::filesystem::path& path);
/// Writes `v` lines with 9 significant digits, then `f` lines (1-based).
void writeObj(const std::filesystem::path& path, const Mesh& mesh);

/// PLY: element `vertex` with float/double (or any numeric) x, y, z among other properties,
/// element `face` with a list property `vertex_indices` or `vertex_index`; other elements skipped.
Mesh readPly(const std::filesystem::path& path);
/// Binary: float32 xyz and uchar/int32 faces, little-endian. Ascii: the same as text with
/// 9 significant digits (so a double survives to float precision).
void writePly(const std::filesystem::path& path, const Mesh& mesh, PlyEncoding encoding = PlyEncoding::Binary);

} // namespace facesketch

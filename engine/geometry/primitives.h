#pragma once
// Meshes with known geometry, for tests (normals, rendering, later curvature) and demos.

#include "core/mesh.h"

namespace facesketch {

/// An icosahedron subdivided `subdivisions` times (each splits every triangle in four) with all
/// vertices projected onto the sphere of `radius` about the origin. 10 * 4^s + 2 vertices;
/// triangles counter-clockwise seen from outside.
Mesh makeIcosphere(double radius, int subdivisions);

} // namespace facesketch

namespace facesketch {

/// A rectangular height-field patch: nx by ny vertices over [-width/2, width/2] x
/// [-height/2, height/2] in the xy plane at z = 0, two triangles per cell, counter-clockwise
/// seen from +z. Vertex (i, j) is row j * nx + i.
Mesh makeGrid(int nx, int ny, double width, double height);

} // namespace facesketch

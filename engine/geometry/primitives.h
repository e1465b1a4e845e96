#pragma once
// Meshes with known geometry, for tests (normals, rendering, later curvature) and demos.

#include "core/mesh.h"

namespace facesketch {

/// An icosahedron subdivided `subdivisions` times (each splits every triangle in four) with all
/// vertices projected onto the sphere of `radius` about the origin. 10 * 4^s + 2 vertices;
/// triangles counter-clockwise seen from outside.
Mesh makeIcosphere(double radius, int subdivisions);

/// A torus about the z axis: tube centre radius R, tube radius r < R; ringSegments around z,
/// tubeSegments around the tube. Vertex (i, j) at ring angle 2 pi i / ringSegments and tube
/// angle v = 2 pi j / tubeSegments is ((R + r cos v) cos u, (R + r cos v) sin u, r sin v).
/// Closed. Principal curvatures (outward normals, convex positive): 1/r around the tube and
/// cos v / (R + r cos v) around z.
Mesh makeTorus(double R, double r, int ringSegments, int tubeSegments);

/// An open cylinder of `radius` about the z axis from z = 0 to z = length, `segments` around
/// and `rings` + 1 vertex rings along z. Curvatures: 1/radius and 0.
Mesh makeCylinder(double radius, double length, int segments, int rings);

/// A rectangular height-field patch: nx by ny vertices over [-width/2, width/2] x
/// [-height/2, height/2] in the xy plane at z = 0, two triangles per cell, counter-clockwise
/// seen from +z. Vertex (i, j) is row j * nx + i.
Mesh makeGrid(int nx, int ny, double width, double height);

} // namespace facesketch

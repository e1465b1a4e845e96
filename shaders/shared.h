// Constants shared by C++ and GLSL: workgroup sizes, binding numbers, flags.
// Included by engine code as "shaders/shared.h" and by shaders as "shared.h".
#ifndef FACESKETCH_SHADERS_SHARED_H
#define FACESKETCH_SHADERS_SHARED_H

// Batched per-vertex vectors of many meshes with one topology are stored mesh-minor as vec4
// ("batch layout"): vertex v of mesh m at index v * meshCount + m, w unused. Neighbouring
// invocations then work on the same vertex of neighbouring meshes: the topology reads and the
// loop trip counts are uniform, and each position is one 16-byte load.
#define BATCH_GROUP_MESHES 8    // invocations along meshes (x); one SIMD row on lavapipe
#define BATCH_GROUP_VERTICES 8  // invocations along vertices (y)

// normals.comp: area-weighted vertex normals for a batch of meshes sharing one topology.
#define NORMALS_BINDING_POSITIONS 0     // float, batch layout
#define NORMALS_BINDING_WEDGE_OFFSETS 1 // uint[vertexCount + 1], CSR offsets into wedges
#define NORMALS_BINDING_WEDGES 2        // uvec2[]: the other two corners of each incident triangle, in winding order
#define NORMALS_BINDING_NORMALS 3       // float, batch layout; unit length or zero

// mesh.vert / mesh.frag: one vertex layout and one pipeline layout for triangles, lines, points.
#define DRAW_MODE_LIT 0     // Lambert + specular from a head light, two-sided
#define DRAW_MODE_UNLIT 1   // vertex colour as is
#define DRAW_MODE_POINTS 2  // unlit round points

#endif

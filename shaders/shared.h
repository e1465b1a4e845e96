// Constants shared by C++ and GLSL: workgroup sizes, binding numbers, flags.
// Included by engine code as "shaders/shared.h" and by shaders as "shared.h".
#ifndef FACESKETCH_SHADERS_SHARED_H
#define FACESKETCH_SHADERS_SHARED_H

// normals.comp: area-weighted vertex normals for a batch of meshes sharing one topology.
#define NORMALS_GROUP_SIZE 64
#define NORMALS_BINDING_POSITIONS 0   // float[mesh][vertex][3]
#define NORMALS_BINDING_WEDGE_OFFSETS 1 // uint[vertexCount + 1], CSR offsets into wedges
#define NORMALS_BINDING_WEDGES 2      // uvec2[]: the other two corners of each incident triangle, in winding order
#define NORMALS_BINDING_NORMALS 3     // float[mesh][vertex][3], unit length or zero

// mesh.vert / mesh.frag: one vertex layout and one pipeline layout for triangles, lines, points.
#define DRAW_MODE_LIT 0     // Lambert + specular from a head light, two-sided
#define DRAW_MODE_UNLIT 1   // vertex colour as is
#define DRAW_MODE_POINTS 2  // unlit round points

#endif

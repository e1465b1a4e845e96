#version 450
#extension GL_GOOGLE_include_directive : require
// Area-weighted vertex normals: n(v) = normalize(sum over triangles t at v of cross(b - v, c - v)),
// where (v, b, c) is t in its winding order; |cross| is twice t's area, hence the area weight.
// One invocation per (vertex, mesh); a gather over the vertex's wedges, so no atomics and the
// result does not depend on scheduling. Zero-area neighbourhoods give a zero normal.
#include "shared.h"

layout(local_size_x = NORMALS_GROUP_SIZE, local_size_y = 1, local_size_z = 1) in;

layout(binding = NORMALS_BINDING_POSITIONS, std430) readonly buffer Positions { float positions[]; };
layout(binding = NORMALS_BINDING_WEDGE_OFFSETS, std430) readonly buffer WedgeOffsets { uint wedgeOffsets[]; };
layout(binding = NORMALS_BINDING_WEDGES, std430) readonly buffer Wedges { uvec2 wedges[]; };
layout(binding = NORMALS_BINDING_NORMALS, std430) writeonly buffer Normals { float normals[]; };

layout(push_constant) uniform Constants {
    uint vertexCount;
    uint meshCount;
};

vec3 position(uint base, uint v)
{
    uint i = base + 3 * v;
    return vec3(positions[i], positions[i + 1], positions[i + 2]);
}

void main()
{
    uint v = gl_GlobalInvocationID.x;
    uint mesh = gl_GlobalInvocationID.y;
    if (v >= vertexCount || mesh >= meshCount)
        return;
    uint base = mesh * vertexCount * 3;
    vec3 p = position(base, v);
    vec3 sum = vec3(0.0);
    for (uint w = wedgeOffsets[v]; w < wedgeOffsets[v + 1]; ++w) {
        uvec2 bc = wedges[w];
        sum += cross(position(base, bc.x) - p, position(base, bc.y) - p);
    }
    float len = length(sum);
    vec3 n = len > 0.0 ? sum / len : vec3(0.0);
    uint o = base + 3 * v;
    normals[o] = n.x;
    normals[o + 1] = n.y;
    normals[o + 2] = n.z;
}

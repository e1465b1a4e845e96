#version 450
#extension GL_GOOGLE_include_directive : require
// Vertex normals: n(v) = normalize(sum over triangles t at v of w_t cross(b - v, c - v)), where
// (v, b, c) is t in its winding order. |cross| is twice t's area, so w_t = 1 weights by area
// (NORMALS_WEIGHT_AREA); w_t = 1 / (|b - v|^2 |c - v|^2) is Max 1999 (NORMALS_WEIGHT_MAX).
// One invocation per (mesh, vertex), meshes along x: a gather over the vertex's wedges, so no
// atomics and a result independent of scheduling. Zero-area neighbourhoods give a zero normal.
#include "shared.h"

layout(local_size_x = BATCH_GROUP_MESHES, local_size_y = BATCH_GROUP_VERTICES, local_size_z = 1) in;

layout(binding = NORMALS_BINDING_POSITIONS) uniform samplerBuffer positions; // (T) RGBA32F
layout(binding = NORMALS_BINDING_WEDGE_OFFSETS) uniform usamplerBuffer wedgeOffsets; // (T) R32UI
layout(binding = NORMALS_BINDING_WEDGES) uniform usamplerBuffer wedges; // (T) RG32UI
layout(binding = NORMALS_BINDING_NORMALS, std430) restrict writeonly buffer Normals { vec4 normals[]; };

layout(push_constant) uniform Constants { NORMALS_CONSTANTS_MEMBERS };

vec3 position(uint v, uint mesh)
{
    return texelFetch(positions, int(v * meshCount + mesh)).xyz;
}

void main()
{
    uint mesh = gl_GlobalInvocationID.x;
    if (mesh >= meshCount)
        return;
    // One vertex per invocation (batchRows): no loop around the body, which lavapipe runs
    // several times slower than the same code outside a loop.
    uint v = gl_GlobalInvocationID.y;
    if (v < vertexCount) {
        vec3 p = position(v, mesh);
        vec3 sum = vec3(0.0);
        for (uint w = texelFetch(wedgeOffsets, int(v)).x; w < texelFetch(wedgeOffsets, int(v + 1)).x; ++w) {
            uvec2 bc = texelFetch(wedges, int(w)).xy;
            vec3 a = position(bc.x, mesh) - p, b = position(bc.y, mesh) - p;
            float weight = 1.0;
            if (weighting == NORMALS_WEIGHT_MAX) {
                float l2 = dot(a, a) * dot(b, b);
                weight = l2 > 0.0 ? 1.0 / l2 : 0.0;
            }
            sum += weight * cross(a, b);
        }
        float len = length(sum);
        vec3 n = len > 0.0 ? sum / len : vec3(0.0);
        normals[v * meshCount + mesh] = vec4(n, 0.0);
    }
}

#version 450
#extension GL_GOOGLE_include_directive : require
// Principal curvatures and directions per vertex (Rusinkiewicz 2004), for a batch of meshes.
// One invocation per (mesh, vertex) gathers over the vertex's triangles: each triangle's second
// fundamental form is fitted to the normal differences along its edges (3x3 least squares),
// turned into the vertex's tangent frame and weighted by the vertex's Voronoi corner area.
// CPU reference: engine/contours/curvature.cpp. Convex is positive; k1 >= k2.
#include "shared.h"

layout(local_size_x = BATCH_GROUP_MESHES, local_size_y = BATCH_GROUP_VERTICES, local_size_z = 1) in;

layout(binding = CURVATURE_BINDING_POSITIONS) uniform samplerBuffer positions; // (T) RGBA32F
layout(binding = CURVATURE_BINDING_WEDGE_OFFSETS) uniform usamplerBuffer wedgeOffsets; // (T) R32UI
layout(binding = CURVATURE_BINDING_WEDGES) uniform usamplerBuffer wedges; // (T) RG32UI
layout(binding = CURVATURE_BINDING_NORMALS) uniform samplerBuffer normals; // (T) RGBA32F
layout(binding = CURVATURE_BINDING_CURVATURE, std430) restrict writeonly buffer Curvatures { vec4 curvatures[]; }; // k1, k2, area, 0
layout(binding = CURVATURE_BINDING_DIRECTIONS, std430) restrict writeonly buffer Directions { vec4 directions[]; }; // dir1, 0

layout(push_constant) uniform Constants { BATCH_CONSTANTS_MEMBERS };

#include "curvature_common.glsl"

// Solves the symmetric 3x3 system [a00 a01 0; a01 a11 a12; 0 a12 a22] x = r (the face fit's
// normal equations) by Cramer's rule; returns zero when singular.
vec3 solveTridiagonal(float a00, float a01, float a11, float a12, float a22, vec3 r)
{
    float det = a00 * (a11 * a22 - a12 * a12) - a01 * a01 * a22;
    if (abs(det) < 1e-30)
        return vec3(0.0);
    float x = (r.x * (a11 * a22 - a12 * a12) - a01 * (r.y * a22 - a12 * r.z)) / det;
    float y = (a00 * (r.y * a22 - a12 * r.z) - r.x * a01 * a22) / det;
    float z = (a00 * (a11 * r.z - r.y * a12) - a01 * (a01 * r.z) + r.x * a01 * a12) / det;
    return vec3(x, y, z);
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
        uint index = v * meshCount + mesh;
        vec3 p = loadBatch(v, mesh).xyz;
        vec3 n = texelFetch(normals, int(index)).xyz;
        uint first = texelFetch(wedgeOffsets, int(v)).x, last = texelFetch(wedgeOffsets, int(v + 1)).x;
        vec3 tensor = vec3(0.0);
        float area = 0.0;
        vec3 pdir1 = vec3(0.0), pdir2 = vec3(0.0);
        bool frame = false;
        if (first < last && length(n) > 0.0) {
            vec3 edge = loadBatch(texelFetch(wedges, int(first)).x, mesh).xyz - p;
            vec3 tangent = edge - dot(edge, n) * n;
            if (length(tangent) > 0.0) {
                pdir1 = normalize(tangent);
                pdir2 = cross(n, pdir1);
                frame = true;
            }
        }
        for (uint w = first; frame && w < last; ++w) {
            uvec2 bc = texelFetch(wedges, int(w)).xy;
            vec3 pb = loadBatch(bc.x, mesh).xyz, pc = loadBatch(bc.y, mesh).xyz;
            vec3 nb = texelFetch(normals, int(bc.x * meshCount + mesh)).xyz, nc = texelFetch(normals, int(bc.y * meshCount + mesh)).xyz;
            // Corners (v, b, c); edges opposite each.
            vec3 e0 = pc - pb, e1 = p - pc, e2 = pb - p;
            vec3 fn = cross(e0, e1);
            if (!(length(fn) > 0.0) || !(length(e0) > 0.0))
                continue;
            vec3 t = normalize(e0);
            vec3 b = cross(normalize(fn), t);
            // Normal differences along e0 (c - b), e1 (v - c), e2 (b - v).
            vec3 dn0 = nc - nb, dn1 = n - nc, dn2 = nb - n;
            vec3 u = vec3(dot(e0, t), dot(e1, t), dot(e2, t));
            vec3 vv = vec3(dot(e0, b), dot(e1, b), dot(e2, b));
            vec3 dnu = vec3(dot(dn0, t), dot(dn1, t), dot(dn2, t));
            vec3 dnv = vec3(dot(dn0, b), dot(dn1, b), dot(dn2, b));
            float a00 = dot(u, u), a01 = dot(u, vv), a11 = dot(u, u) + dot(vv, vv), a22 = dot(vv, vv);
            vec3 r = vec3(dot(dnu, u), dot(dnu, vv) + dot(dnv, u), dot(dnv, vv));
            vec3 efg = solveTridiagonal(a00, a01, a11, a01, a22, r);
            float corner = cornerAreas(e0, e1, e2).x;
            tensor += corner * projectTensor(t, b, efg, pdir1, pdir2);
            area += corner;
        }
        vec4 curvature = vec4(0.0);
        vec4 direction = vec4(0.0);
        if (frame && area > 0.0) {
            vec3 T = tensor / area;
            // Eigen-decomposition of [[T.x T.y] [T.y T.z]].
            float mean = 0.5 * (T.x + T.z);
            float radius = sqrt(0.25 * (T.x - T.z) * (T.x - T.z) + T.y * T.y);
            float k1 = mean + radius, k2 = mean - radius;
            vec2 e = abs(T.x - k1) + abs(T.y) > abs(T.z - k1) + abs(T.y) ? vec2(T.y, k1 - T.x) : vec2(k1 - T.z, T.y);
            if (!(length(e) > 0.0))
                e = vec2(1.0, 0.0); // umbilic: any direction is principal
            e = normalize(e);
            curvature = vec4(k1, k2, area, 0.0);
            direction = vec4(normalize(e.x * pdir1 + e.y * pdir2), 0.0);
        }
        curvatures[index] = curvature;
        directions[index] = direction;
    }
}

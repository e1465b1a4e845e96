#version 450
#extension GL_GOOGLE_include_directive : require
// Derivative of curvature per vertex (Rusinkiewicz 2004), for a batch of meshes, after
// curvature.comp. One invocation per (mesh, vertex) gathers over the vertex's triangles: the
// three corners' curvature tensors are read in the triangle's frame, the symmetric 3-tensor C
// is fitted to their differences along the edges (4x4 least squares), read in the vertex's
// principal frame and weighted by the Voronoi corner area. Output (C111, C112, C122, C222) in
// the (dir1, dir2) frame. CPU reference: engine/contours/curvature.cpp.
#include "shared.h"

layout(local_size_x = BATCH_GROUP_MESHES, local_size_y = BATCH_GROUP_VERTICES, local_size_z = 1) in;

layout(binding = DCURV_BINDING_POSITIONS) uniform samplerBuffer positions; // (T) RGBA32F
layout(binding = DCURV_BINDING_WEDGE_OFFSETS) uniform usamplerBuffer wedgeOffsets; // (T) R32UI
layout(binding = DCURV_BINDING_WEDGES) uniform usamplerBuffer wedges; // (T) RG32UI
layout(binding = DCURV_BINDING_NORMALS) uniform samplerBuffer normals; // (T) RGBA32F
layout(binding = DCURV_BINDING_CURVATURE) uniform samplerBuffer curvatures; // (T) RGBA32F
layout(binding = DCURV_BINDING_DIRECTIONS) uniform samplerBuffer directions; // (T) RGBA32F
layout(binding = DCURV_BINDING_DERIVATIVE, std430) restrict writeonly buffer Derivatives { vec4 derivatives[]; };
layout(binding = DCURV_BINDING_SHAPE, std430) restrict writeonly buffer Shapes { uvec4 shapes[]; };
layout(binding = DCURV_BINDING_SHAPE_C23, std430) restrict writeonly buffer ShapesC23 { uint shapesC23[]; };

layout(push_constant) uniform Constants { BATCH_CONSTANTS_MEMBERS };

#include "curvature_common.glsl"
#include "octahedral.glsl"

// The curvature tensor of vertex `v` read in the frame (t, b).
vec3 vertexTensorIn(uint v, vec3 t, vec3 b)
{
    uint index = v * meshCount + gl_GlobalInvocationID.x;
    vec3 n = texelFetch(normals, int(index)).xyz;
    vec3 d1 = texelFetch(directions, int(index)).xyz;
    vec4 k = texelFetch(curvatures, int(index));
    return projectTensor(d1, cross(n, d1), vec3(k.x, 0.0, k.y), t, b);
}

// The symmetric 3-tensor c = (C111, C112, C122, C222) in frame (u, v), read in frame (ru, rv).
vec4 projectDerivative(vec3 u, vec3 v, vec4 c, vec3 ru, vec3 rv)
{
    rotateFrame(u, v, cross(ru, rv));
    vec2 x = vec2(dot(ru, u), dot(ru, v)), y = vec2(dot(rv, u), dot(rv, v));
    // C(p, p, p), C(p, p, q), C(p, q, q), C(q, q, q) for the symmetric tensor.
    return vec4(c.x * x.x * x.x * x.x + 3.0 * c.y * x.x * x.x * x.y + 3.0 * c.z * x.x * x.y * x.y + c.w * x.y * x.y * x.y,
                c.x * x.x * x.x * y.x + c.y * (x.x * x.x * y.y + 2.0 * x.x * x.y * y.x) +
                    c.z * (2.0 * x.x * x.y * y.y + x.y * x.y * y.x) + c.w * x.y * x.y * y.y,
                c.x * x.x * y.x * y.x + c.y * (2.0 * x.x * y.x * y.y + x.y * y.x * y.x) +
                    c.z * (x.x * y.y * y.y + 2.0 * x.y * y.x * y.y) + c.w * x.y * y.y * y.y,
                c.x * y.x * y.x * y.x + 3.0 * c.y * y.x * y.x * y.y + 3.0 * c.z * y.x * y.y * y.y + c.w * y.y * y.y * y.y);
}

// Solves A x = r for the fit's normal equations, which are symmetric and tridiagonal:
// diagonal (a.x, a.y, a.z, a.w), off-diagonal o (all three equal), by Cholesky; zero when not
// positive definite. Straight-line code: lavapipe keeps a matrix indexed in loops in memory.
vec4 solveTridiagonal4(vec4 a, float o, vec4 r)
{
    float l00 = sqrt(a.x), l10 = o / l00;
    float d1 = a.y - l10 * l10;
    float l11 = sqrt(d1), l21 = o / l11;
    float d2 = a.z - l21 * l21;
    float l22 = sqrt(d2), l32 = o / l22;
    float d3 = a.w - l32 * l32;
    float l33 = sqrt(d3);
    float y0 = r.x / l00, y1 = (r.y - l10 * y0) / l11, y2 = (r.z - l21 * y1) / l22, y3 = (r.w - l32 * y2) / l33;
    float x3 = y3 / l33, x2 = (y2 - l32 * x3) / l22, x1 = (y1 - l21 * x2) / l11, x0 = (y0 - l10 * x1) / l00;
    bool definite = all(greaterThan(vec4(a.x, d1, d2, d3), vec4(1e-30)));
    return mix(vec4(0.0), vec4(x0, x1, x2, x3), bvec4(definite));
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
        vec4 k = texelFetch(curvatures, int(index));
        float area = k.z;
        vec3 n = texelFetch(normals, int(index)).xyz;
        vec3 d1 = texelFetch(directions, int(index)).xyz;
        vec3 d2 = cross(n, d1);
        vec3 kv = vec3(k.x, 0.0, k.y); // the vertex's own tensor in (d1, d2)
        vec3 p = loadBatch(v, mesh).xyz;
        vec4 sum = vec4(0.0);
        for (uint w = texelFetch(wedgeOffsets, int(v)).x; area > 0.0 && w < texelFetch(wedgeOffsets, int(v + 1)).x; ++w) {
            uvec2 bc = texelFetch(wedges, int(w)).xy;
            vec3 pb = loadBatch(bc.x, mesh).xyz, pc = loadBatch(bc.y, mesh).xyz;
            vec3 e0 = pc - pb, e1 = p - pc, e2 = pb - p;
            vec3 fn = cross(e0, e1);
            if (!(length(fn) > 0.0) || !(length(e0) > 0.0))
                continue;
            vec3 t = normalize(e0);
            vec3 b = cross(normalize(fn), t);
            vec3 c0 = projectTensor(d1, d2, kv, t, b), c1 = vertexTensorIn(bc.x, t, b), c2 = vertexTensorIn(bc.y, t, b);
            // Tensor differences along e0 (c - b), e1 (v - c), e2 (b - v). Each edge (u, w) in
            // the frame (t, b) gives three equations, rows (u, w, 0, 0), (0, u, w, 0), (0, 0, u, w)
            // against its difference's (x, y, z): their normal equations, written out.
            vec3 eu = vec3(dot(e0, t), dot(e1, t), dot(e2, t)), ew = vec3(dot(e0, b), dot(e1, b), dot(e2, b));
            vec3 dx = vec3(c2.x - c1.x, c0.x - c2.x, c1.x - c0.x), dy = vec3(c2.y - c1.y, c0.y - c2.y, c1.y - c0.y),
                 dz = vec3(c2.z - c1.z, c0.z - c2.z, c1.z - c0.z);
            float suu = dot(eu, eu), suw = dot(eu, ew), sww = dot(ew, ew);
            vec4 r = vec4(dot(eu, dx), dot(ew, dx) + dot(eu, dy), dot(ew, dy) + dot(eu, dz), dot(ew, dz));
            vec4 C = solveTridiagonal4(vec4(suu, suu + sww, suu + sww, sww), suw, r);
            float corner = cornerAreas(e0, e1, e2).x;
            sum += corner * projectDerivative(t, b, C, d1, d2);
        }
        vec4 C = area > 0.0 ? sum / area : vec4(0.0);
        derivatives[index] = C;
        bool valid = area > 0.0 && length(n) > 0.0 && length(d1) > 0.0;
        shapes[index] = valid ? uvec4(packSnorm2x16(octEncode(n)), packSnorm2x16(octEncode(d1)), packHalf2x16(k.xy), packHalf2x16(C.xy))
                              : uvec4(0u);
        shapesC23[index] = valid ? packHalf2x16(C.zw) : 0u;
    }
}

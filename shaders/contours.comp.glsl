#version 450
#extension GL_GOOGLE_include_directive : require
// Per-view contour tests for every (mesh, vertex) of a batch and the candidate cloud, appended
// with an atomic counter. The tests, thresholds and culling are those of
// engine/contours/candidates.h, whose CPU reference this follows.
#include "shared.h"

layout(local_size_x = BATCH_GROUP_MESHES, local_size_y = BATCH_GROUP_VERTICES, local_size_z = 1) in;

layout(binding = CONTOURS_BINDING_POSITIONS, std430) restrict readonly buffer Positions { vec4 positions[]; };
layout(binding = CONTOURS_BINDING_SHAPE, std430) restrict readonly buffer Shapes { uvec4 shapes[]; };
layout(binding = CONTOURS_BINDING_SHAPE_C23, std430) restrict readonly buffer ShapesC23 { uint shapesC23[]; };
layout(binding = CONTOURS_BINDING_WEDGE_OFFSETS, std430) restrict readonly buffer WedgeOffsets { uint wedgeOffsets[]; };
layout(binding = CONTOURS_BINDING_WEDGES, std430) restrict readonly buffer Wedges { uvec2 wedges[]; };
layout(binding = CONTOURS_BINDING_FLAGS, std430) restrict readonly buffer Flags { uint flags[]; };
layout(binding = CONTOURS_BINDING_VIEW, std140) uniform View {
    mat4 viewProjection;
    vec4 eye;        // xyz; w = 1 for perspective, 0 for orthographic
    vec4 toCameraOrtho;
    vec4 rect;       // x0, y0, x1, y1 in pixels
    vec4 sphere;     // centre, radius in mm
    vec4 thresholds; // silhouette, suggestive, featureSize^2, 0
    vec4 screen;     // width, height
    uvec4 counts;    // vertexCount, meshCount, capacity, 0
};
#include "octahedral.glsl"

struct Candidate {
    uvec4 ids;   // mesh, vertex, types, 0
    vec4 world;  // xyz, depth
    vec4 pixel;  // x, y
};
layout(binding = CONTOURS_BINDING_OUTPUT, std430) buffer Output {
    uint count;
    uint pad0, pad1, pad2;
    Candidate candidates[];
};

vec3 toCamera(vec3 p)
{
    return eye.w > 0.5 ? normalize(eye.xyz - p) : toCameraOrtho.xyz;
}

// Radial curvature and its derivative along w (contours/curvature.h, radialCurvature) from a
// packed shape. Returns (kr, dwkr, ndotv).
vec3 radial(uvec4 shape, uint index, vec3 v, bool withDerivative)
{
    vec3 n = octDecode(unpackSnorm2x16(shape.x));
    float ndotv = dot(n, v);
    vec3 w = v - ndotv * n;
    vec3 d1 = octDecode(unpackSnorm2x16(shape.y));
    float u = dot(w, d1), t = dot(w, cross(n, d1));
    float s2 = u * u + t * t;
    if (!(s2 > 1e-24))
        return vec3(0.0, 0.0, ndotv);
    vec2 k = unpackHalf2x16(shape.z);
    float kr = (k.x * u * u + k.y * t * t) / s2;
    float dwkr = 0.0;
    if (withDerivative) {
        vec4 d = vec4(unpackHalf2x16(shape.w), unpackHalf2x16(shapesC23[index]));
        float s = sqrt(s2);
        float cwww = (d.x * u * u * u + 3.0 * d.y * u * u * t + 3.0 * d.z * u * t * t + d.w * t * t * t) / (s2 * s);
        dwkr = cwww + 2.0 * k.x * k.y * ndotv / s;
    }
    return vec3(kr, dwkr, ndotv);
}

void main()
{
    uint mesh = gl_GlobalInvocationID.x;
    uint vertexCount = counts.x, meshCount = counts.y;
    if (mesh >= meshCount)
        return;
    uint stride = gl_NumWorkGroups.y * gl_WorkGroupSize.y;
    for (uint v = gl_GlobalInvocationID.y; v < vertexCount; v += stride) {
        uint flag = flags[v];
        if ((flag & VERTEX_EXCLUDED) != 0u)
            continue;
        uint index = v * meshCount + mesh;
        vec3 p = positions[index].xyz;
        // Culling first: most vertices lie outside a stroke's rectangle.
        vec4 clip = viewProjection * vec4(p, 1.0);
        vec3 ndc = clip.xyz / clip.w;
        vec2 pixel = vec2((ndc.x + 1.0) * 0.5 * screen.x, (1.0 - ndc.y) * 0.5 * screen.y);
        if (pixel.x < rect.x || pixel.x > rect.z || pixel.y < rect.y || pixel.y > rect.w || length(p - sphere.xyz) > sphere.w)
            continue;

        uvec4 shape = shapes[index];
        if (shape.x == 0u && shape.y == 0u)
            continue; // no tangent plane
        vec3 r = radial(shape, index, toCamera(p), true);
        uint types = 0u;
        if (abs(r.z) < thresholds.x)
            types |= CONTOUR_SILHOUETTE;
        if (r.z > 0.0 && r.y * thresholds.z > thresholds.y) {
            for (uint w = wedgeOffsets[v]; w < wedgeOffsets[v + 1] && (types & CONTOUR_SUGGESTIVE) == 0u; ++w) {
                uvec2 bc = wedges[w];
                for (int j = 0; j < 2; ++j) {
                    uint u = j == 0 ? bc.x : bc.y;
                    uint ui = u * meshCount + mesh;
                    uvec4 neighbour = shapes[ui];
                    if (neighbour.x == 0u && neighbour.y == 0u)
                        continue;
                    float b = radial(neighbour, ui, toCamera(positions[ui].xyz), false).x;
                    bool crossing = (r.x < 0.0) != (b < 0.0);
                    bool nearer = abs(r.x) < abs(b) || (abs(r.x) == abs(b) && v < u);
                    if (crossing && nearer)
                        types |= CONTOUR_SUGGESTIVE;
                }
            }
        }
        if ((flag & VERTEX_LABELLED) != 0u && r.z > -thresholds.x)
            types |= CONTOUR_LABELLED;
        if (types == 0u)
            continue;
        uint slot = atomicAdd(count, 1u);
        if (slot < counts.z)
            candidates[slot] = Candidate(uvec4(mesh, v, types, 0u), vec4(p, ndc.z), vec4(pixel, 0.0, 0.0));
    }
}

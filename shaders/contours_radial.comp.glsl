#version 450
#extension GL_GOOGLE_include_directive : require
// Pass 1 of the per-view contour tests (engine/contours/candidates.h, whose CPU reference this
// follows): for every (mesh, vertex) the radial curvature k_r, which pass 2 reads for the
// neighbours' zero-crossing test, and the vertex's own tests, culled to the view's rectangle and
// sphere: silhouette, labelled, and the suggestive pre-test (front-facing, D_w k_r l^2 over
// threshold). Every lane does the same work: no branch a SIMD row would run for one lane.
#include "shared.h"

layout(local_size_x = BATCH_GROUP_MESHES, local_size_y = BATCH_GROUP_VERTICES, local_size_z = 1) in;

layout(binding = CONTOURS_BINDING_POSITIONS, std430) restrict readonly buffer Positions { vec4 positions[]; };
layout(binding = CONTOURS_BINDING_SHAPE, std430) restrict readonly buffer Shapes { uvec4 shapes[]; };
layout(binding = CONTOURS_BINDING_SHAPE_C23, std430) restrict readonly buffer ShapesC23 { uint shapesC23[]; };
layout(binding = CONTOURS_BINDING_FLAGS, std430) restrict readonly buffer Flags { uint flags[]; };
layout(binding = CONTOURS_BINDING_RADIAL, std430) restrict writeonly buffer Radial { float radialOut[]; };
layout(binding = CONTOURS_BINDING_STATE, std430) restrict writeonly buffer State { uint state[]; };
layout(binding = CONTOURS_BINDING_VERTEX_LIST, std430) restrict readonly buffer VertexList { uint vertexList[]; };
#include "contours_view.glsl"
#include "octahedral.glsl"

void main()
{
    uint mesh = gl_GlobalInvocationID.x;
    uint meshCount = counts.y;
    if (mesh >= meshCount)
        return;
    uint stride = gl_NumWorkGroups.y * gl_WorkGroupSize.y;
    for (uint i = gl_GlobalInvocationID.y; i < counts.w; i += stride) {
        uint v = vertexList[i];
        uint index = v * meshCount + mesh;
        vec3 p = positions[index].xyz;
        uvec4 shape = shapes[index];
        vec3 n = octDecode(unpackSnorm2x16(shape.x));
        vec3 view = toCamera(p);
        float ndotv = dot(n, view);
        // k_r = k1 cos^2 + k2 sin^2 of the angle between w (the view vector projected on the
        // tangent plane) and dir1; D_w k_r from the derivative tensor C (contours/curvature.h).
        vec3 w = view - ndotv * n;
        vec3 d1 = octDecode(unpackSnorm2x16(shape.y));
        float u = dot(w, d1), t = dot(w, cross(n, d1));
        float s2 = max(u * u + t * t, 1e-30);
        vec2 k = unpackHalf2x16(shape.z);
        vec4 c = vec4(unpackHalf2x16(shape.w), unpackHalf2x16(shapesC23[index]));
        float s = sqrt(s2);
        float kr = (k.x * u * u + k.y * t * t) / s2;
        float cwww = (c.x * u * u * u + 3.0 * c.y * u * u * t + 3.0 * c.z * u * t * t + c.w * t * t * t) / (s2 * s);
        float dwkr = cwww + 2.0 * k.x * k.y * ndotv / s;
        bool plane = !(shape.x == 0u && shape.y == 0u);
        bool radialDefined = plane && u * u + t * t > 1e-24;
        radialOut[index] = plane ? (radialDefined ? kr : 0.0) : CONTOURS_NO_RADIAL;

        vec3 pixel = project(p);
        bool inside = pixel.x >= rect.x && pixel.x <= rect.z && pixel.y >= rect.y && pixel.y <= rect.w &&
                      length(p - sphere.xyz) <= sphere.w;
        uint flag = flags[v];
        uint bits = 0u;
        if (abs(ndotv) < thresholds.x)
            bits |= CONTOUR_SILHOUETTE;
        if (radialDefined && ndotv > 0.0 && dwkr * thresholds.z > thresholds.y)
            bits |= CONTOURS_TEST_SUGGESTIVE;
        if ((flag & VERTEX_LABELLED) != 0u && ndotv > -thresholds.x)
            bits |= CONTOUR_LABELLED;
        state[index] = plane && inside && (flag & VERTEX_EXCLUDED) == 0u ? bits : 0u;
    }
}

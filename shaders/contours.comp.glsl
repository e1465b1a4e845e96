#version 450
#extension GL_GOOGLE_include_directive : require
// Pass 2 of the per-view contour tests (engine/contours/candidates.h): for every (mesh, vertex)
// that passed a test in pass 1 (contours_radial.comp.glsl), the suggestive zero-crossing test
// against its one-ring's radial curvatures, then the candidate appended with an atomic counter.
#include "shared.h"

layout(local_size_x = BATCH_GROUP_MESHES, local_size_y = BATCH_GROUP_VERTICES, local_size_z = 1) in;

layout(binding = CONTOURS_BINDING_POSITIONS, std430) restrict readonly buffer Positions { vec4 positions[]; };
layout(binding = CONTOURS_BINDING_RADIAL, std430) restrict readonly buffer Radial { float radial[]; };
layout(binding = CONTOURS_BINDING_STATE, std430) restrict readonly buffer State { uint state[]; };
layout(binding = CONTOURS_BINDING_NEIGHBOUR_OFFSETS, std430) restrict readonly buffer NeighbourOffsets { uint neighbourOffsets[]; };
layout(binding = CONTOURS_BINDING_NEIGHBOURS, std430) restrict readonly buffer Neighbours { uint neighbours[]; };
layout(binding = CONTOURS_BINDING_VERTEX_LIST, std430) restrict readonly buffer VertexList { uint vertexList[]; };
#include "contours_view.glsl"

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
        uint bits = state[index];
        if (bits == 0u)
            continue;
        uint types = bits & (CONTOUR_SILHOUETTE | CONTOUR_LABELLED);
        if ((bits & CONTOURS_TEST_SUGGESTIVE) != 0u) {
            // A zero crossing of k_r on an edge marks its end nearer zero (ties: lower index).
            float a = radial[index];
            for (uint i = neighbourOffsets[v]; i < neighbourOffsets[v + 1]; ++i) {
                uint u = neighbours[i];
                float b = radial[u * meshCount + mesh];
                bool crossing = b != CONTOURS_NO_RADIAL && (a < 0.0) != (b < 0.0);
                bool nearer = abs(a) < abs(b) || (abs(a) == abs(b) && v < u);
                if (crossing && nearer)
                    types |= CONTOUR_SUGGESTIVE;
            }
        }
        if (types == 0u)
            continue;
        vec3 p = positions[index].xyz;
        vec3 pixel = project(p);
        uint slot = atomicAdd(count, 1u);
        if (slot < counts.z)
            candidates[slot] = Candidate(uvec4(mesh, v, types, 0u), vec4(p, pixel.z), vec4(pixel.xy, 0.0, 0.0));
    }
}

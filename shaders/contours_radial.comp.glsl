#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require
// Pass 1 of the per-view contour tests (engine/contours/candidates.h, whose CPU reference this
// follows): for every (mesh, vertex) the radial curvature k_r, which pass 2 reads for the
// neighbours' zero-crossing test, and the vertex's own tests: silhouette, labelled, and the
// suggestive pre-test (front-facing, and with the vertex-strength filter D_w k_r l^2 over
// threshold; rtsc's filter is pass 2's). Both go out as one radial word
// (shaders/shared.h), and the pairs that passed a test are listed for pass 2. Culling to the
// rectangle and sphere is pass 2's, which projects the vertices it appends anyway. Every lane
// does the same work: no branch a SIMD row would run for one lane.
// Each invocation does CONTOURS_MESHES_PER_INVOCATION meshes of one vertex, and lists them all
// with one atomic per subgroup: on lavapipe the listing's ballot, atomic and broadcast cost as
// much per subgroup as a good part of the arithmetic (BENCHMARKS.md, "Why the kernels look as they do").
#include "shared.h"

// A workgroup does every mesh of a few vertices (up to 256 meshes) rather than 64 meshes of many
// vertices, so that each core reads one stretch of the batch layout: the gathers here wait on
// memory more than on anything else (BENCHMARKS.md).
layout(local_size_x = CONTOURS_GROUP_MESH_INVOCATIONS, local_size_y = CONTOURS_GROUP_VERTICES, local_size_z = 1) in;

layout(binding = CONTOURS_BINDING_POSITIONS) uniform samplerBuffer positions;
layout(binding = CONTOURS_BINDING_SHAPE) uniform usamplerBuffer shapes;
layout(binding = CONTOURS_BINDING_SHAPE_C23) uniform usamplerBuffer shapesC23;
layout(binding = CONTOURS_BINDING_VERTEX_LIST) uniform usamplerBuffer vertexList;
layout(binding = CONTOURS_BINDING_SIGN_LOCKS) uniform usamplerBuffer signLocks;
layout(binding = CONTOURS_BINDING_RADIAL_OUT, std430) restrict writeonly buffer Radial { uint radialOut[]; };
layout(binding = CONTOURS_BINDING_WORK, std430) restrict buffer Work {
    uvec3 appendGroups; // pass 2's indirect dispatch size
    uint pairCount;
    uint pairs[];
};
#include "contours_view.glsl"
#include "octahedral.glsl"
#include "contours_shape.glsl"

// The radial word of the pair at batch index `index`, whose vertex has VertexFlag bits `flag`;
// `listed` says whether pass 2 must visit it.
uint radialWord(int index, uint flag, out bool listed)
{
    ViewedShape v = viewedShape(index);
    float ndotv = v.ndotv, u = v.u, t = v.t, s2 = v.s2;
    vec2 k = v.k;
    // k_r = k1 cos^2 + k2 sin^2 of the angle between w (the view vector projected on the
    // tangent plane) and dir1; D_w k_r from the derivative tensor C (contours/curvature.h).
    float s = sqrt(s2);
    float kr = (k.x * u * u + k.y * t * t) / s2;
    float dwkr = cwww(v) + 2.0 * k.x * k.y * ndotv / s;
    // Selections by mix() and all() rather than if, ?: and &&, which glslang turns into
    // branches (BENCHMARKS.md, "Why the kernels look as they do").
    bool plane = v.plane;
    bool radialDefined = all(bvec2(plane, u * u + t * t > 1e-24));
    // +0 where undefined or zero, so that the word's sign is k_r's "below zero".
    kr = mix(0.0, clamp(kr, -1e30, 1e30), all(bvec2(radialDefined, kr != 0.0)));

    // rtsc's filter (thresholds.w >= 0) is tested at the crossing, in pass 2: no strength here.
    bool rtsc = thresholds.w >= 0.0;
    // Where k_r keeps its sign on the whole one-ring for any view (GpuCulling::signLockTexels)
    // no zero crossing can mark the vertex: pass 2 need not look at its neighbours.
    bool locked = ((texelFetch(signLocks, index >> 5).x >> (uint(index) & 31u)) & 1u) != 0u;
    uint bits = mix(0u, CONTOUR_SILHOUETTE, abs(ndotv) < thresholds.x) |
                mix(0u, CONTOUR_SUGGESTIVE, all(bvec4(radialDefined, ndotv > 0.0, any(bvec2(dwkr * thresholds.z > thresholds.y, rtsc)), !locked))) |
                mix(0u, CONTOUR_LABELLED, all(bvec2((flag & VERTEX_LABELLED) != 0u, ndotv > -thresholds.x)));
    bits = mix(bits, 0u, (flag & VERTEX_EXCLUDED) != 0u);
    listed = all(bvec2(plane, bits != 0u));
    return mix(CONTOURS_NO_RADIAL, (floatBitsToUint(kr) & ~CONTOURS_STATE_MASK) | bits, plane);
}

void main()
{
    // Invocation x's meshes are first + j * BATCH_GROUP_MESHES: at each step j the lanes of a
    // row do neighbouring meshes, so their reads and stores are contiguous.
    uint x = gl_GlobalInvocationID.x;
    uint first = x / BATCH_GROUP_MESHES * (BATCH_GROUP_MESHES * CONTOURS_MESHES_PER_INVOCATION) + x % BATCH_GROUP_MESHES;
    uint meshCount = counts.y;
    uint i = gl_GlobalInvocationID.y;
    if (first >= meshCount || i >= counts.w)
        return;
    uvec2 listed = texelFetch(vertexList, int(i)).xy; // vertex, flags
    uint row = listed.x * meshCount;
    bool pass[CONTOURS_MESHES_PER_INVOCATION];
    uvec4 ballots[CONTOURS_MESHES_PER_INVOCATION];
    uint total = 0u;
    for (uint j = 0u; j < CONTOURS_MESHES_PER_INVOCATION; ++j) {
        uint mesh = first + j * BATCH_GROUP_MESHES;
        bool valid = mesh < meshCount;
        uint index = row + min(mesh, meshCount - 1u); // past the end: computed, not stored
        uint word = radialWord(int(index), listed.y, pass[j]);
        if (valid)
            radialOut[index] = word;
        pass[j] = pass[j] && valid;
        ballots[j] = subgroupBallot(pass[j]);
        total += subgroupBallotBitCount(ballots[j]);
    }

    // List the pairs for pass 2: one atomic per subgroup, which also grows pass 2's size.
    uint base = 0u;
    if (subgroupElect() && total > 0u) {
        base = atomicAdd(pairCount, total);
        atomicMax(appendGroups.x, (base + total + CONTOURS_GROUP_PAIRS - 1u) / CONTOURS_GROUP_PAIRS);
    }
    base = subgroupBroadcastFirst(base);
    for (uint j = 0u; j < CONTOURS_MESHES_PER_INVOCATION; ++j) {
        if (pass[j])
            pairs[base + subgroupBallotExclusiveBitCount(ballots[j])] = row + first + j * BATCH_GROUP_MESHES;
        base += subgroupBallotBitCount(ballots[j]);
    }
}

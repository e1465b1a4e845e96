#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require
// Pass 2 of the per-view contour tests (engine/contours/candidates.h): for every (mesh, vertex)
// that pass 1 (contours_radial.comp.glsl) listed as having passed a test, the suggestive
// zero-crossing test against its one-ring's radial words (compiled with CONTOURS_RTSC, as
// contours_rtsc_comp, also rtsc's filter at the crossing from both ends' shapes), culling to the view's rectangle and
// sphere, then the candidate appended with an atomic counter. Dispatched indirectly, with the
// size pass 1 wrote.
#include "shared.h"

layout(local_size_x = CONTOURS_GROUP_PAIRS, local_size_y = 1, local_size_z = 1) in;

layout(binding = CONTOURS_BINDING_POSITIONS) uniform samplerBuffer positions;
layout(binding = CONTOURS_BINDING_SHAPE) uniform usamplerBuffer shapes;
layout(binding = CONTOURS_BINDING_SHAPE_C23) uniform usamplerBuffer shapesC23;
layout(binding = CONTOURS_BINDING_RADIAL) uniform usamplerBuffer radial;
layout(binding = CONTOURS_BINDING_NEIGHBOUR_OFFSETS) uniform usamplerBuffer neighbourOffsets;
layout(binding = CONTOURS_BINDING_NEIGHBOURS) uniform usamplerBuffer neighbours;
layout(binding = CONTOURS_BINDING_WORK_TEXELS) uniform usamplerBuffer work;
#include "contours_view.glsl"
#include "octahedral.glsl"
#include "contours_shape.glsl"

#ifdef CONTOURS_RTSC
// rtsc's suggestive filter at one end of an edge (contours/candidates.h, SuggestiveFilter): the
// numerator l^2 rtscNumerator - threshold n.v of tan(theta) D_w k_r l^2 - threshold, and its
// denominator n.v; both interpolate linearly to the edge's zero crossing of k_r.
vec2 rtscEnd(int index)
{
    ViewedShape v = viewedShape(index);
    float torsion = (v.k.y - v.k.x) * v.u * v.t / v.s2;
    float numerator = sqrt(v.s2) * cwww(v) - 2.0 * v.ndotv * torsion * torsion;
    return vec2(thresholds.z * numerator - thresholds.w * v.ndotv, v.ndotv);
}
#endif

struct Candidate { CONTOURS_CANDIDATE_MEMBERS };
layout(binding = CONTOURS_BINDING_OUTPUT, std430) buffer Output {
    uint count;
    uint pad0, pad1, pad2;
    Candidate candidates[];
};

void main()
{
    uint slot = gl_GlobalInvocationID.x;
    if (slot >= texelFetch(work, 3).x) // pair count
        return;
    uint meshCount = counts.y;
    uint index = texelFetch(work, int(CONTOURS_WORK_HEADER + slot)).x;
    uint v = index / meshCount, mesh = index % meshCount;
    uint word = texelFetch(radial, int(index)).x;
    uint bits = word & CONTOURS_STATE_MASK;
    uint types = bits & (CONTOUR_SILHOUETTE | CONTOUR_LABELLED);
    // A zero crossing of k_r on an edge marks its end nearer zero (ties: lower index). The loop
    // runs zero times unless the vertex passed the pre-test.
    float a = uintBitsToFloat(word & ~CONTOURS_STATE_MASK);
    uint begin = texelFetch(neighbourOffsets, int(v)).x;
    uint end = (bits & CONTOUR_SUGGESTIVE) != 0u ? texelFetch(neighbourOffsets, int(v + 1u)).x : begin;
    for (uint k = begin; k < end; ++k) {
        uint u = texelFetch(neighbours, int(k)).x;
        uint other = texelFetch(radial, int(u * meshCount + mesh)).x;
        float b = uintBitsToFloat(other & ~CONTOURS_STATE_MASK);
        bool crossing = other != CONTOURS_NO_RADIAL && (a < 0.0) != (b < 0.0);
        bool nearer = abs(a) < abs(b) || (abs(a) == abs(b) && v < u);
#ifdef CONTOURS_RTSC
        if (crossing && nearer) { // rtsc's filter, at the crossing
            vec2 at = mix(rtscEnd(int(index)), rtscEnd(int(u * meshCount + mesh)), a / (a - b));
            if (at.x > 0.0 && at.y > 0.0)
                types |= CONTOUR_SUGGESTIVE;
        }
#else
        if (crossing && nearer)
            types |= CONTOUR_SUGGESTIVE;
#endif
    }
    vec3 p = texelFetch(positions, int(index)).xyz;
    vec3 pixel = project(p);
    bool inside = pixel.x >= rect.x && pixel.x <= rect.z && pixel.y >= rect.y && pixel.y <= rect.w &&
                  length(p - sphere.xyz) <= sphere.w;
    // Append with one atomic per subgroup rather than one per candidate: every core's
    // candidates go through this one counter.
    bool append = types != 0u && inside;
    uvec4 ballot = subgroupBallot(append);
    uint appended = subgroupBallotBitCount(ballot);
    uint base = 0u;
    if (subgroupElect() && appended > 0u)
        base = atomicAdd(count, appended);
    uint at = subgroupBroadcastFirst(base) + subgroupBallotExclusiveBitCount(ballot);
    if (append && at < counts.z)
        candidates[at] = Candidate(uvec4(mesh, v, types, 0u), vec4(p, pixel.z), vec4(pixel.xy, 0.0, 0.0));
}

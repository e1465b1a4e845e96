// Constants and structs shared by C++ and GLSL: workgroup sizes, binding numbers and counts,
// flags, push-constant and uniform blocks. Included by engine code as "shaders/shared.h" and by
// shaders as "shared.h". Each is defined once, here; why the kernels are shaped as they are, as
// measured on lavapipe, is in BENCHMARKS.md ("Why the kernels look as they do").
//
// Blocks: a block's members are a macro (`NAME_MEMBERS`) of GLSL declarations using only
// uint, float, vec4, uvec4 and mat4, the vectors and matrices first, so that they have the same
// offsets under std140 and std430 and in C++. A shader declares the block around them:
//   layout(push_constant) uniform Constants { NORMALS_CONSTANTS_MEMBERS };
// and C++ gets the struct `facesketch::shaders::Name` below, whose size and offsets are checked
// with static_assert. Comments inside the member macros are /* */: a // comment would swallow
// the line continuation.
#ifndef FACESKETCH_SHADERS_SHARED_H
#define FACESKETCH_SHADERS_SHARED_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
// GLSL's types under their GLSL names, for the member macros (float is float in both; so is
// the unsigned literal suffix u).
namespace facesketch::shaders {
using uint = std::uint32_t;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
} // namespace facesketch::shaders
#endif

// The bit of binding `b` in a program's texel or uniform mask (gpu::createComputeProgram).
#define BINDING_BIT(b) (1u << (b))

// Batched per-vertex vectors of many meshes with one topology are stored mesh-minor as vec4
// ("batch layout"): vertex v of mesh m at index v * meshCount + m, w unused. Neighbouring
// invocations then work on the same vertex of neighbouring meshes: the topology reads and the
// loop trip counts are uniform, and each position is one 16-byte load.
#define BATCH_GROUP_MESHES   8 // invocations along meshes (x); one SIMD row on lavapipe
#define BATCH_GROUP_VERTICES 8 // invocations along vertices (y)

// normals.comp: area-weighted vertex normals for a batch of meshes sharing one topology.
// (T) marks texel-buffer bindings (gpu::TexelView): read-only data each invocation reads at its
// own address.
#define NORMALS_BINDING_POSITIONS     0 // (T) RGBA32F, batch layout
#define NORMALS_BINDING_WEDGE_OFFSETS 1 // (T) R32UI [vertexCount + 1], CSR offsets into wedges
#define NORMALS_BINDING_WEDGES        2 // (T) RG32UI: the other two corners of each incident triangle, in winding order
#define NORMALS_BINDING_NORMALS       3 // float, batch layout; unit length or zero
#define NORMALS_BINDING_COUNT         4
#define NORMALS_TEXEL_BINDINGS                                                                                                             \
    (BINDING_BIT(NORMALS_BINDING_POSITIONS) | BINDING_BIT(NORMALS_BINDING_WEDGE_OFFSETS) | BINDING_BIT(NORMALS_BINDING_WEDGES))
#define NORMALS_WEIGHT_AREA 0 // each triangle weighted by its area
#define NORMALS_WEIGHT_MAX  1 // Max 1999: each corner by 1 / (|e1|^2 |e2|^2), exact on spheres
// Push constants of normals.comp.
#define NORMALS_CONSTANTS_MEMBERS                                                                                                          \
    uint vertexCount;                                                                                                                      \
    uint meshCount;                                                                                                                        \
    uint weighting; /* NORMALS_WEIGHT_* */

// curvature.comp: principal curvatures and directions (Rusinkiewicz 2004), batch layout.
#define CURVATURE_BINDING_POSITIONS     0 // (T), as in normals.comp
#define CURVATURE_BINDING_WEDGE_OFFSETS 1 // (T)
#define CURVATURE_BINDING_WEDGES        2 // (T)
#define CURVATURE_BINDING_NORMALS       3 // (T) RGBA32F: Max-weighted normals (normals.comp, NORMALS_WEIGHT_MAX)
#define CURVATURE_BINDING_CURVATURE     4 // out: k1, k2 (1/mm, k1 >= k2, convex positive), Voronoi area, 0
#define CURVATURE_BINDING_DIRECTIONS    5 // out: dir1 (unit, tangent), 0; dir2 = normal x dir1
#define CURVATURE_BINDING_COUNT         6
#define CURVATURE_TEXEL_BINDINGS                                                                                                           \
    (BINDING_BIT(CURVATURE_BINDING_POSITIONS) | BINDING_BIT(CURVATURE_BINDING_WEDGE_OFFSETS) | BINDING_BIT(CURVATURE_BINDING_WEDGES)       \
        | BINDING_BIT(CURVATURE_BINDING_NORMALS))
// Push constants of curvature.comp and curvature_derivative.comp.
#define BATCH_CONSTANTS_MEMBERS                                                                                                            \
    uint vertexCount;                                                                                                                      \
    uint meshCount;

// curvature_derivative.comp: derivative of curvature, after curvature.comp.
#define DCURV_BINDING_POSITIONS     0 // (T) inputs 0-5, as in curvature.comp
#define DCURV_BINDING_WEDGE_OFFSETS 1 // (T)
#define DCURV_BINDING_WEDGES        2 // (T)
#define DCURV_BINDING_NORMALS       3 // (T)
#define DCURV_BINDING_CURVATURE     4 // (T)
#define DCURV_BINDING_DIRECTIONS    5 // (T)
#define DCURV_BINDING_DERIVATIVE    6 // out: C111, C112, C122, C222 in the (dir1, dir2) frame
#define DCURV_BINDING_SHAPE         7 // out: uvec4 packed for the contour tests (below), 0 where undefined
#define DCURV_BINDING_SHAPE_C23     8 // out: uint, packHalf2x16(C122, C222)
#define DCURV_BINDING_COUNT         9
#define DCURV_TEXEL_BINDINGS                                                                                                               \
    (BINDING_BIT(DCURV_BINDING_POSITIONS) | BINDING_BIT(DCURV_BINDING_WEDGE_OFFSETS) | BINDING_BIT(DCURV_BINDING_WEDGES)                   \
        | BINDING_BIT(DCURV_BINDING_NORMALS) | BINDING_BIT(DCURV_BINDING_CURVATURE) | BINDING_BIT(DCURV_BINDING_DIRECTIONS))
// The packed "shape" of a vertex, all the per-view contour tests read besides its position:
// x = packSnorm2x16(octahedral(normal)), y = packSnorm2x16(octahedral(dir1)),
// z = packHalf2x16(k1, k2), w = packHalf2x16(C111, C112); plus SHAPE_C23. 24 bytes instead of 64
// (octahedral unit vectors: Cigolle et al., JCGT 2014). A vertex without a tangent plane
// (zero normal) is all zeros, which no valid vertex can be (dir1 is never parallel to normal).

// mesh.vert / mesh.frag: one vertex layout and one pipeline layout for triangles, lines, points.
#define DRAW_MODE_LIT    0 // Lambert + specular from a head light, two-sided
#define DRAW_MODE_UNLIT  1 // vertex colour as is
#define DRAW_MODE_POINTS 2 // unlit round points
// Push constants of mesh.vert and mesh.frag.
#define DRAW_CONSTANTS_MEMBERS                                                                                                             \
    mat4 viewProjection;                                                                                                                   \
    vec4 toLight;      /* xyz: unit vector towards the head light (world) */                                                               \
    uint mode;         /* DRAW_MODE_* */                                                                                                   \
    float pointSize;   /* pixels */                                                                                                        \
    float depthOffset; /* pulls lines and points towards the camera, in NDC depth units */

// Push constants of overlay.frag: the overlay image's size and the viewport's, in pixels.
#define OVERLAY_CONSTANTS_MEMBERS                                                                                                          \
    uint imageWidth;                                                                                                                       \
    uint imageHeight;                                                                                                                      \
    float targetWidth;                                                                                                                     \
    float targetHeight;

// The per-view contour tests and the candidate cloud (thesis 4.3, 4.4) in two passes, so that
// the suggestive zero-crossing test reads one word per neighbour instead of recomputing its
// radial curvature (engine/contours/candidates_gpu.h).
// contours_radial.comp (pass 1): per (mesh, vertex), the radial curvature and the vertex's own
// tests: silhouette, labelled, and the suggestive pre-test (front-facing, D_w k_r over
// threshold, and not sign-locked: GpuCulling::signLockTexels), and the list of the pairs that
// passed one, so that pass 2 visits only those (one atomic per subgroup), and the indirect
// dispatch size. Each invocation does CONTOURS_MESHES_PER_INVOCATION meshes of its vertex.
// contours.comp (pass 2): for each listed pair, the suggestive zero-crossing test against the
// one-ring, culling to the rectangle and sphere, and the atomic append.
#define CONTOURS_GROUP_MESH_INVOCATIONS 32  // pass 1: workgroups of 32 x 4 invocations (meshes x vertices),
#define CONTOURS_GROUP_VERTICES         4   //   256 meshes of 4 vertices
#define CONTOURS_MESHES_PER_INVOCATION  8u  // pass 1: meshes per invocation, so 64 per SIMD row and per listing atomic
#define CONTOURS_GROUP_PAIRS            256 // pass 2: workgroups of 256 listed pairs
// Both passes share one binding layout.
#define CONTOURS_BINDING_POSITIONS 0 // (T) RGBA32F, batch layout
#define CONTOURS_BINDING_SHAPE     1 // (T) RGBA32UI: DCURV_BINDING_SHAPE
#define CONTOURS_BINDING_SHAPE_C23 2 // (T) R32UI: DCURV_BINDING_SHAPE_C23
// 3, (T) RG32UI [counts.w]: the vertices pass 1 visits, ascending, and their VERTEX_LABELLED |
// VERTEX_EXCLUDED flags (the host leaves out those no mesh shows in the view, keeping one-rings).
#define CONTOURS_BINDING_VERTEX_LIST       3
#define CONTOURS_BINDING_VIEW              4 // uniform ContourView (below)
#define CONTOURS_BINDING_RADIAL_OUT        5 // out: uint, batch layout, the radial word (below)
#define CONTOURS_BINDING_RADIAL            6 // (T) R32UI view of RADIAL_OUT
#define CONTOURS_BINDING_NEIGHBOUR_OFFSETS 7 // (T) R32UI [vertexCount + 1]
#define CONTOURS_BINDING_NEIGHBOURS        8 // (T) R32UI: one-rings, geometry/wedges.h buildNeighbours
#define CONTOURS_BINDING_OUTPUT            9 // uint count, 3 pad, then candidates: ContourCandidate (below)
// 10, out: the uvec3 indirect dispatch size of pass 2 (the host sets 0, 1, 1), the uint pair
// count, then the listed pairs' batch indices v * meshCount + mesh.
#define CONTOURS_BINDING_WORK        10
#define CONTOURS_BINDING_WORK_TEXELS 11 // (T) R32UI view of WORK
#define CONTOURS_BINDING_SIGN_LOCKS  12 // (T) R32UI: GpuCulling::signLockTexels (pass 1: no suggestive pre-test where set)
#define CONTOURS_BINDING_COUNT       13
#define CONTOURS_TEXEL_BINDINGS                                                                                                            \
    (BINDING_BIT(CONTOURS_BINDING_POSITIONS) | BINDING_BIT(CONTOURS_BINDING_SHAPE) | BINDING_BIT(CONTOURS_BINDING_SHAPE_C23)               \
        | BINDING_BIT(CONTOURS_BINDING_VERTEX_LIST) | BINDING_BIT(CONTOURS_BINDING_RADIAL)                                                 \
        | BINDING_BIT(CONTOURS_BINDING_NEIGHBOUR_OFFSETS) | BINDING_BIT(CONTOURS_BINDING_NEIGHBOURS)                                       \
        | BINDING_BIT(CONTOURS_BINDING_WORK_TEXELS) | BINDING_BIT(CONTOURS_BINDING_SIGN_LOCKS))
#define CONTOURS_UNIFORM_BINDINGS BINDING_BIT(CONTOURS_BINDING_VIEW)
#define CONTOURS_WORK_HEADER      4u // uints before the pairs in WORK
#define CONTOURS_OUTPUT_HEADER    4u // uints before the candidates in OUTPUT
// The View block of both passes (std140, shaders/contours_view.glsl).
#define CONTOURS_VIEW_MEMBERS                                                                                                              \
    mat4 viewProjection;                                                                                                                   \
    vec4 eye;        /* perspective: the eye, 1; orthographic: the unit vector towards the camera, 0 */                                    \
    vec4 rect;       /* x0, y0, x1, y1 in pixels */                                                                                        \
    vec4 sphere;     /* centre, radius in mm */                                                                                            \
    vec4 thresholds; /* silhouette, suggestive, featureSize^2, rtsc (< 0: vertex strength) */                                              \
    vec4 screen;     /* width, height */                                                                                                   \
    uvec4 counts;    /* vertexCount, meshCount, capacity, listed vertices */
// One appended candidate in OUTPUT (std430).
#define CONTOURS_CANDIDATE_MEMBERS                                                                                                         \
    uvec4 ids;  /* mesh, vertex, CONTOUR_* bits, 0 */                                                                                      \
    vec4 world; /* position in mm, depth in [0, 1] */                                                                                      \
    vec4 pixel; /* x, y in pixels, 0, 0 */
// The radial word: the bits of k_r as a float whose three lowest mantissa bits are replaced by
// the vertex's own results (CONTOUR_SILHOUETTE, CONTOUR_LABELLED, and CONTOUR_SUGGESTIVE for
// "passed the pre-test, check the one-ring"), or CONTOURS_NO_RADIAL without a tangent plane.
// Dropping 3 of 23 mantissa bits moves k_r by under 1e-6 of itself, far inside the tie
// tolerance of the CPU comparison (1e-3 of |k1| + |k2|), and keeps its sign.
#define CONTOURS_STATE_MASK 7u
#define CONTOURS_NO_RADIAL  0x7f800000u // +inf with no state bits: never a candidate, no k_r
// Contour types of a candidate (contours/candidates.h ContourType).
#define CONTOUR_SILHOUETTE 1u
#define CONTOUR_SUGGESTIVE 2u
#define CONTOUR_LABELLED   4u
// Per-vertex flags of a topology (contours/candidates.h VertexFlag).
#define VERTEX_LABELLED 1u
#define VERTEX_EXCLUDED 2u

#ifdef __cplusplus
namespace facesketch::shaders {

struct alignas(16) NormalsConstants {
    NORMALS_CONSTANTS_MEMBERS
};
static_assert(sizeof(NormalsConstants) == 16 && offsetof(NormalsConstants, weighting) == 8);

struct alignas(16) BatchConstants {
    BATCH_CONSTANTS_MEMBERS
};
static_assert(sizeof(BatchConstants) == 16 && offsetof(BatchConstants, meshCount) == 4);

struct alignas(16) DrawConstants {
    DRAW_CONSTANTS_MEMBERS
};
static_assert(sizeof(DrawConstants) == 96 && offsetof(DrawConstants, toLight) == 64 && offsetof(DrawConstants, mode) == 80
    && offsetof(DrawConstants, depthOffset) == 88);

struct alignas(16) OverlayConstants {
    OVERLAY_CONSTANTS_MEMBERS
};
static_assert(sizeof(OverlayConstants) == 16);

struct ContourView {
    CONTOURS_VIEW_MEMBERS
};
// std140 and std430 agree here: a mat4, then vec4s and a uvec4, each at a multiple of 16.
static_assert(sizeof(ContourView) == 64 + 6 * 16);
static_assert(offsetof(ContourView, eye) == 64 && offsetof(ContourView, rect) == 80 && offsetof(ContourView, sphere) == 96
    && offsetof(ContourView, thresholds) == 112 && offsetof(ContourView, screen) == 128 && offsetof(ContourView, counts) == 144);

struct ContourCandidate {
    CONTOURS_CANDIDATE_MEMBERS
};
static_assert(sizeof(ContourCandidate) == 48 && offsetof(ContourCandidate, world) == 16 && offsetof(ContourCandidate, pixel) == 32);

// Every binding fits its program's count, and no binding is both texel and uniform.
static_assert(NORMALS_TEXEL_BINDINGS < BINDING_BIT(NORMALS_BINDING_COUNT));
static_assert(CURVATURE_TEXEL_BINDINGS < BINDING_BIT(CURVATURE_BINDING_COUNT));
static_assert(DCURV_TEXEL_BINDINGS < BINDING_BIT(DCURV_BINDING_COUNT));
static_assert((CONTOURS_TEXEL_BINDINGS | CONTOURS_UNIFORM_BINDINGS) < BINDING_BIT(CONTOURS_BINDING_COUNT));
static_assert((CONTOURS_TEXEL_BINDINGS & CONTOURS_UNIFORM_BINDINGS) == 0);
static_assert(CONTOURS_OUTPUT_HEADER * 4 == 16, "the candidates start at a 16-byte boundary (std430 uvec4)");

} // namespace facesketch::shaders
#endif

#endif

// Constants shared by C++ and GLSL: workgroup sizes, binding numbers, flags.
// Included by engine code as "shaders/shared.h" and by shaders as "shared.h".
#ifndef FACESKETCH_SHADERS_SHARED_H
#define FACESKETCH_SHADERS_SHARED_H

// Batched per-vertex vectors of many meshes with one topology are stored mesh-minor as vec4
// ("batch layout"): vertex v of mesh m at index v * meshCount + m, w unused. Neighbouring
// invocations then work on the same vertex of neighbouring meshes: the topology reads and the
// loop trip counts are uniform, and each position is one 16-byte load.
#define BATCH_GROUP_MESHES   8 // invocations along meshes (x); one SIMD row on lavapipe
#define BATCH_GROUP_VERTICES 8 // invocations along vertices (y)

// normals.comp: area-weighted vertex normals for a batch of meshes sharing one topology.
#define NORMALS_BINDING_POSITIONS     0    // (T) RGBA32F, batch layout
#define NORMALS_BINDING_WEDGE_OFFSETS 1    // (T) R32UI [vertexCount + 1], CSR offsets into wedges
#define NORMALS_BINDING_WEDGES        2    // (T) RG32UI: the other two corners of each incident triangle, in winding order
#define NORMALS_BINDING_NORMALS       3    // float, batch layout; unit length or zero
#define NORMALS_WEIGHT_AREA           0    // each triangle weighted by its area
#define NORMALS_WEIGHT_MAX            1    // Max 1999: each corner by 1 / (|e1|^2 |e2|^2), exact on spheres
#define NORMALS_TEXEL_BINDINGS        0x7u // bits of the (T) bindings: read-only data as texel buffers (gpu::TexelView)

// curvature.comp: principal curvatures and directions (Rusinkiewicz 2004), batch layout.
#define CURVATURE_BINDING_POSITIONS     0 // (T), as in normals.comp
#define CURVATURE_BINDING_WEDGE_OFFSETS 1 // (T)
#define CURVATURE_BINDING_WEDGES        2 // (T)
#define CURVATURE_BINDING_NORMALS       3 // (T) RGBA32F: Max-weighted normals (normals.comp, NORMALS_WEIGHT_MAX)
#define CURVATURE_BINDING_CURVATURE     4 // out: k1, k2 (1/mm, k1 >= k2, convex positive), Voronoi area, 0
#define CURVATURE_BINDING_DIRECTIONS    5 // out: dir1 (unit, tangent), 0; dir2 = normal x dir1
#define CURVATURE_TEXEL_BINDINGS        0xFu

// curvature_derivative.comp: derivative of curvature, after curvature.comp.
#define DCURV_BINDING_POSITIONS     0 // (T) inputs 0-5, as in curvature.comp
#define DCURV_BINDING_WEDGE_OFFSETS 1
#define DCURV_BINDING_WEDGES        2
#define DCURV_BINDING_NORMALS       3
#define DCURV_BINDING_CURVATURE     4
#define DCURV_BINDING_DIRECTIONS    5
#define DCURV_TEXEL_BINDINGS        0x3Fu
#define DCURV_BINDING_DERIVATIVE    6 // out: C111, C112, C122, C222 in the (dir1, dir2) frame
#define DCURV_BINDING_SHAPE         7 // out: uvec4 packed for the contour tests (below), 0 where undefined
#define DCURV_BINDING_SHAPE_C23     8 // out: uint, packHalf2x16(C122, C222)
// The packed "shape" of a vertex, all the per-view contour tests read besides its position:
// x = packSnorm2x16(octahedral(normal)), y = packSnorm2x16(octahedral(dir1)),
// z = packHalf2x16(k1, k2), w = packHalf2x16(C111, C112); plus SHAPE_C23. 24 bytes instead of 64
// (octahedral unit vectors: Cigolle et al., JCGT 2014). A vertex without a tangent plane
// (zero normal) is all zeros, which no valid vertex can be (dir1 is never parallel to normal).

// mesh.vert / mesh.frag: one vertex layout and one pipeline layout for triangles, lines, points.
#define DRAW_MODE_LIT    0 // Lambert + specular from a head light, two-sided
#define DRAW_MODE_UNLIT  1 // vertex colour as is
#define DRAW_MODE_POINTS 2 // unlit round points

// The per-view contour tests and the candidate cloud (thesis 4.3, 4.4) in two passes, so that
// the suggestive zero-crossing test reads one word per neighbour instead of recomputing its
// radial curvature. Written for lavapipe (Mesa 22.3) as much as for GPUs, where it measured:
// - every storage-buffer access at a per-invocation address is a scalar loop over the 8 lanes
//   of a SIMD row, and it runs (masked) even where no lane takes the branch around it, so the
//   kernels keep few of them: large read-only data are texel buffers (one vector gather per
//   row), pass 1 writes a single word per (mesh, vertex) and lists pairs with one atomic per
//   subgroup, and pass 2 stores only what it appends, also with one atomic per subgroup;
// - listing costs per subgroup: a ballot, an elected atomic on the one shared counter and a
//   broadcast took about 10 ms per 150,000 subgroups in a microbenchmark, half of it the
//   counter's cache line moving between the two cores. So each pass 1 invocation does
//   CONTOURS_MESHES_PER_INVOCATION meshes of its vertex (a loop of constant trip count), and a
//   subgroup lists 64 pairs at once: the whole view took 29% less;
// - a branch is run for every lane of a row when any lane takes it, so every lane does the
//   same work in pass 1 and the neighbour loop of pass 2 has a trip count of zero where the
//   vertex failed the pre-test. glslang makes branches of if, of ?: and && on anything but
//   plain operands, and lavapipe then runs both sides with masks: pass 1 selects with mix()
//   and all() instead (the ?: of toCamera alone cost 10% of a whole view);
// - the body of a loop with a varying trip count costs several times the same code outside
//   one (a grid-stride loop around the whole kernel halved its speed), so no kernel loops over
//   vertices.
// contours_radial.comp: per (mesh, vertex), the radial curvature and the vertex's own tests:
// silhouette, labelled, and the suggestive pre-test (front-facing, D_w k_r over threshold, and
// not sign-locked: GpuCurvature::signLockTexels, which takes a quarter of the pre-test's pairs
// off pass 2), and the list of the pairs that passed one (a sixth of them on faces), so that
// pass 2 visits only those: one atomic per subgroup (ballot), and the indirect dispatch size.
// (T) marks texel-buffer bindings (gpu::TexelView).
#define CONTOURS_GROUP_MESH_INVOCATIONS 32  // pass 1: workgroups of 32 x 4 invocations (meshes x vertices),
#define CONTOURS_GROUP_VERTICES         4   //   256 meshes of 4 vertices (whole view 6-9% faster than 8 x 32 at 5,230)
#define CONTOURS_MESHES_PER_INVOCATION  8u  // pass 1: meshes per invocation, so 64 per SIMD row and per listing atomic
#define CONTOURS_GROUP_PAIRS            256 // pass 2: workgroups of 256 listed pairs
#define CONTOURS_BINDING_POSITIONS      0   // (T) RGBA32F, batch layout
#define CONTOURS_BINDING_SHAPE          1   // (T) RGBA32UI: DCURV_BINDING_SHAPE
#define CONTOURS_BINDING_SHAPE_C23      2   // (T) R32UI: DCURV_BINDING_SHAPE_C23
#define CONTOURS_BINDING_VERTEX_LIST                                                                                                       \
    3                                 // (T) RG32UI [counts.w]: the vertices pass 1 visits, ascending, and their
                                      // VERTEX_LABELLED | VERTEX_EXCLUDED flags (the host culls those no mesh
                                      // shows in the rectangle, keeping their one-rings)
#define CONTOURS_BINDING_VIEW       4 // uniform ContourViewGpu (engine/contours/candidates_gpu.cpp)
#define CONTOURS_BINDING_RADIAL_OUT 5 // out: uint, batch layout, the radial word (below)
#define CONTOURS_BINDING_WORK                                                                                                              \
    10 // out: uvec3 indirect dispatch size of pass 2 (host sets 0, 1, 1), uint pair
       // count, then the listed pairs' batch indices v * meshCount + mesh
// contours.comp: for each listed pair, the suggestive zero-crossing test against the one-ring,
// culling to the rectangle and sphere, and the atomic append.
#define CONTOURS_BINDING_RADIAL            6 // (T) R32UI view of RADIAL_OUT
#define CONTOURS_BINDING_NEIGHBOUR_OFFSETS 7 // (T) R32UI [vertexCount + 1]
#define CONTOURS_BINDING_NEIGHBOURS        8 // (T) R32UI: one-rings, geometry/wedges.h buildNeighbours
#define CONTOURS_BINDING_OUTPUT                                                                                                            \
    9 // uint count, 3 pad, then candidates: uvec4(mesh, vertex, types, 0), vec4(world, depth), vec4(screen, 0, 0)
#define CONTOURS_BINDING_WORK_TEXELS 11      // (T) R32UI view of WORK
#define CONTOURS_WORK_HEADER         4u      // uints before the pairs in WORK
#define CONTOURS_BINDING_SIGN_LOCKS  12      // (T) R32UI: GpuCurvature::signLockTexels (pass 1: no suggestive pre-test where set)
#define CONTOURS_TEXEL_BINDINGS      0x19CFu // bits of the (T) bindings above
// The radial word: the bits of k_r as a float whose three lowest mantissa bits are replaced by
// the vertex's own results (CONTOUR_SILHOUETTE, CONTOUR_LABELLED, and CONTOUR_SUGGESTIVE for
// "passed the pre-test, check the one-ring"), or CONTOURS_NO_RADIAL without a tangent plane.
// Dropping 3 of 23 mantissa bits moves k_r by under 1e-6 of itself, far inside the tie
// tolerance of the CPU comparison (1e-3 of |k1| + |k2|), and keeps its sign.
#define CONTOURS_STATE_MASK 7u
#define CONTOURS_NO_RADIAL  0x7f800000u // +inf with no state bits: never a candidate, no k_r
#define CONTOUR_SILHOUETTE  1u
#define CONTOUR_SUGGESTIVE  2u
#define CONTOUR_LABELLED    4u
#define VERTEX_LABELLED     1u
#define VERTEX_EXCLUDED     2u

#endif

#pragma once
// Per-vertex principal curvatures, principal directions and the derivative of curvature of a
// triangle mesh, double precision: the CPU reference for shaders/curvature*.comp.glsl, and what
// the suggestive contour test needs (thesis 4.3.2).
//
// Estimator: Rusinkiewicz, "Estimating Curvatures and Their Derivatives on Triangle Meshes",
// 3DPVT 2004 (the one DeCarlo et al.'s real-time suggestive contours use). Per face, the second
// fundamental form is the least-squares fit of the normal differences along the three edges;
// per vertex, the face tensors are rotated into the vertex's tangent plane and averaged with
// Voronoi corner-area weights (Meyer et al., "Discrete Differential-Geometry Operators for
// Triangulated 2-Manifolds", 2003). The derivative tensor C is fitted the same way from the
// differences of the vertex tensors along the edges. The thesis used Taubin 1995 (4.3.2); this
// estimator also yields C, which the thesis approximated by a finite difference (4.26).
//
// Conventions: normals are weighted as Max 1999 (exact on spheres; the area-weighted normals of
// geometry/normals.h bias the fit by up to 6% at irregular vertices of a sphere), outward for
// counter-clockwise triangles. Curvature is positive where the surface bends away from the
// normal, i.e. convex is positive: a sphere of radius r has k1 = k2 = 1/r with outward normals.
// k1 >= k2 (signed). dir1, dir2 are unit tangent vectors with dir1 x dir2 = normal.

#include "core/mesh.h"

namespace facesketch {

struct Curvature {
    Vertices normal;        ///< #V by 3 unit normals
    Eigen::VectorXd k1, k2; ///< #V principal curvatures, 1/mm, k1 >= k2
    Vertices dir1, dir2;    ///< #V by 3 principal directions
    /// #V by 4 derivative of curvature in the (dir1, dir2) frame: C(d1,d1,d1), C(d1,d1,d2),
    /// C(d1,d2,d2), C(d2,d2,d2), in 1/mm^2. C(x,y,z) is the derivative along x of II(y,z).
    Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> dcurv;
    Eigen::VectorXd area; ///< #V mixed Voronoi area, mm^2 (sums to the mesh area)
};

/// Curvature of `mesh` (validated; isolated vertices get zeros). The vertex frame before
/// diagonalisation starts from the first triangle at each vertex in F's order, which the GPU
/// kernels follow too.
Curvature estimateCurvature(const Mesh& mesh);

/// Radial curvature k_r = II(w, w) / |w|^2 and its derivative along w (DeCarlo et al.,
/// "Interactive Rendering of Suggestive Contours with Temporal Coherence", NPAR 2004:
/// D_w k_r = C(w,w,w)/|w|^3 + 2 K cos(theta) / sin(theta), K = k1 k2), where w is the
/// projection of the unit vector towards the camera `toCamera` onto the tangent plane and
/// theta its angle to the normal. Returns false (and zeros) when w vanishes (view along n).
/// Also rtsc's form of the derivative (DeCarlo and Rusinkiewicz's reference implementation,
/// rtsc 1.6), which replaces 2 K cot(theta) by -2 tau_r^2 cot(theta), tau_r = (k2 - k1) cos phi
/// sin phi the geodesic torsion along w: the two agree where k_r = 0, where they are read.
struct RadialCurvature {
    double kr = 0;
    double dwkr = 0;
    double ndotv = 0;
    /// sin(theta) (C(w,w,w)/|w|^3 - 2 tau_r^2 cot(theta)): the numerator of rtsc's
    /// tan(theta) D_w k_r, whose denominator is ndotv (both interpolate linearly along an edge).
    double rtscNumerator = 0;
};
RadialCurvature radialCurvature(const Curvature& c, Eigen::Index vertex, const Eigen::Vector3d& toCamera);

} // namespace facesketch

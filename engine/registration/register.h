#pragma once
// Registering a scan of any topology into the template's topology (thesis 3.2.8-3.2.12).
//
// 1. The scan's feature points are validated and completed from the template's
//    (registration/feature_points.h, thesis 3.2.6-3.2.7).
// 2. The RBF approximation (registration/rbf.h, thesis 3.2.9) moves every template vertex.
// 3. Registration (thesis 3.2.10) moves each approximated vertex onto the scan along the ray
//    from the cylinder axis fixed by the feature points (registration/depth_map.h), by one of:
//    - depth maps (thesis 3.2.12, the default): the approximation and the scan are rasterised
//      into depth maps over the same grid; where both have data the scan's depth replaces the
//      approximation's. This is done on the difference D = scan - approximation, so that the
//      approximation's own vertices are not moved by its rasterisation error: D is kept where the
//      scan has data within maxDisplacement of the approximation, then faded to 0 over
//      blendPixels beyond the scan's edges and holes (the seam blending of 3.2.12.1), and each
//      vertex moves by D read at its own (theta, h): r' = r + D. Vertices below the outermost
//      surface (lips' inside, eye sockets: the approximation's depth map is deeper than the
//      vertex there) are labelled Occluded and moved by the displacement of the surface that hides
//      them, so they follow it at the same distance (3.2.12.2). Pixels without scan data keep the
//      approximation (labelled Approximation).
//    - projection (thesis 3.2.11): each vertex takes the depth of the scan triangle under it in
//      the unwrapped plane (barycentric, eq. 3.8), the one nearest its own depth where the scan
//      folds; vertices with no scan triangle under them keep the approximation. No blending.
//
// 4. Refinement (options.refinePasses, not in the thesis): the landmarks' RBF is far from the scan
//    away from the landmarks (3-11 mm, p95, on ICT faces: jaw sides, neck), where step 3 moves
//    vertices a long way or, beyond maxDisplacement, not at all. After a pass, the template
//    vertices it read from the scan (label Scan, not grazing), refineSpacing mm apart on the
//    template, are added to the feature points as correspondences (template position ->
//    registered position), the RBF is refitted and step 3 is run again from it.
// 5. Optionally (options.smoothingSteps), the displacement registered - approximation is smoothed
//    over the mesh: it averages the scan's noise, and the detail the approximation lacks.
//
// Grazing vertices (where the thesis' method is weakest). Along a ray from a vertical axis, a
// surface that faces up or down (under the chin and jaw, the nostrils' sides) is crossed almost
// tangentially: a tenth of a millimetre along the axis moves the depth the ray meets by
// millimetres, and the plane of such a scan triangle, read a fraction of a pixel from where the
// map sampled it, is far off (47 mm under the chin of one ICT face; spikes of 16 mm in
// `eval observe` on 250 registered ICT faces). A vertex is grazing when the scan triangle that
// gives its depth (either route), or the approximation's own surface at it, meets its ray at a
// cosine below grazingCosine, or when its read depth is more than maxDisplacement from the
// approximation. Grazing vertices are re-placed after either route: they take the displacement
// of their reliable neighbours, diffused over the mesh (a harmonic fill of each grazing patch
// from its rim), and a visible one is then snapped to the nearest point of the scan if that is
// within grazingSnap mm and not on the scan's border (label Scan; Blended if not snapped). An
// Occluded vertex whose hiding surface is grazing takes the diffused displacement unsnapped.
//
// Reading the merged map back (thesis 3.2.12.3, the aliasing problem). A depth map samples both
// meshes at pixel centres only, so reading it at a vertex between them is off by the meshes'
// creases within a pixel: on the test head of tests/registration (a 642-vertex template, 256 x 256
// maps) bilinear reading left 0.63 mm at the nose tip, the thesis' "crinkled nose" (fig. 3.31).
//   ReadBack::Plane (default): a vertex over scan data takes the depth of the plane of the scan
//     triangle that the map holds at the vertex's pixel, evaluated at the vertex's own (theta, h)
//     (eq. 3.8 on that triangle): the map finds the triangle, the triangle gives the depth, so
//     there is no aliasing. Elsewhere (blended, occluded, missing) as Bilinear.
//   ReadBack::Bilinear: r + D interpolated from the four nearest pixels.
//   ReadBack::Thesis: the thesis' smoothing, r + D of the vertex's own pixel mixed with its
//     left/right and top/bottom neighbours weighted by the vertex's position in the pixel, the
//     neighbours getting `smoothing` of the weight (0 = the nearest pixel alone; the thesis
//     preferred 0.8, fig. 3.35). It smooths scan noise at the cost of detail.

#include "core/mesh.h"
#include "registration/depth_map.h"
#include "registration/feature_points.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace facesketch::registration {

enum class RegistrationMethod { DepthMaps, Projection };
enum class ReadBack { Plane, Bilinear, Thesis };

struct RegistrationOptions {
    RegistrationMethod method = RegistrationMethod::DepthMaps;
    int mapWidth = 512, mapHeight = 512; ///< depth-map pixels
    double blendPixels = 8.0;            ///< width of the seam blend beyond the scan's data, pixels
    ReadBack readBack = ReadBack::Plane;
    double smoothing = 0.8; ///< ReadBack::Thesis only: weight of the neighbouring pixels, [0, 1]
    /// Scan depths farther than this (mm) from the approximation's are another surface (hair,
    /// shoulders, a scanning artefact) and are not used.
    double maxDisplacement = 15.0;
    /// Use the scan only between the ears (obs_r to obs_l about the axis), as thesis 3.2.12.1
    /// did: ears fold over themselves, which a depth map cannot hold, and behind them the
    /// template's head is kept.
    bool betweenEars = true;
    /// A vertex more than this (mm) below the approximation's outermost surface is Occluded.
    double occlusionTolerance = 0.5;
    /// Grazing vertices (see registerScan): where the approximation's surface normal makes an
    /// angle with the ray from the axis whose cosine is below this, the surface is seen edge-on
    /// (under the chin, beside the nostrils) and a depth along the ray is unreliable. 0 turns
    /// the repair off.
    double grazingCosine = 0.35;
    /// A grazing vertex is snapped to the scan only if the nearest scan point is within this
    /// (mm) of where its neighbours' displacement puts it; otherwise it keeps that position.
    double grazingSnap = 3.0;
    /// Refinement passes (see registerScan): after a pass, template vertices that it read from
    /// the scan, refineSpacing mm apart on the template, join the feature points as extra RBF
    /// correspondences (template position -> registered position), and the scan is registered
    /// again from that closer approximation. 0: the thesis' single pass. At most 4.
    int refinePasses = 1;
    double refineSpacing = 12.0; ///< mm on the template between refinement points
    /// Umbrella steps (weight 1/2) smoothing the displacement registered - approximation over
    /// the registered vertices after the last pass: averages the scan's noise, and with it the
    /// detail the approximation lacks (on ICT faces 1 step moves the max distance to the true
    /// surface from about 1.5 to 2.5 mm; docs/registration.md). 0: off.
    int smoothingSteps = 0;
    FeaturePointLimits limits;
    /// Only vertices [firstVertex, endVertex) are registered (e.g. the template's "skin"
    /// component), and only triangles among them rasterised; every other vertex (eyes, teeth)
    /// keeps the RBF approximation. endVertex < 0: up to the last vertex.
    int firstVertex = 0, endVertex = -1;
};

/// Where a registered vertex's position came from.
enum class VertexSource : std::uint8_t {
    Scan,          ///< moved onto the scan's surface
    Blended,       ///< beside the scan's data, moved by the faded seam blend
    Approximation, ///< no scan data: the RBF approximation is kept
    Occluded,      ///< hidden under the outer surface: follows the surface that hides it
};
const char* sourceName(VertexSource source);

struct Registration {
    Vertices approximation;           ///< #V by 3, the RBF approximation (thesis 3.2.9) of the last pass, mm
    Vertices registered;              ///< #V by 3, the registered face, mm
    std::vector<VertexSource> source; ///< #V labels
    CompletedPoints points;           ///< the feature points used, estimated ones included
    CylinderFrame frame;              ///< the unwrapping axis
    DepthGrid grid;                   ///< the depth maps' grid (DepthMaps only)
    int refinementPoints = 0;         ///< RBF correspondences the last refinement pass added
};

/// Registers `scan` (any topology, the template's units) into the template's topology.
/// @param[in] templ           the template face (#V vertices, its triangles)
/// @param[in] templatePoints  the template's feature points (usually its landmark vertices)
/// @param[in] scan            the scan; holes and noise allowed
/// @param[in] scanPoints      the scan's feature points (feature_points.h)
/// @param[in] scanName        names the scan in error messages
/// Throws Error "<scanName>: ..." for an empty scan, a non-finite coordinate, bad feature points
/// or bad options, before computing anything.
Registration registerScan(const Mesh& templ, const FeaturePoints& templatePoints, const Mesh& scan, const FeaturePoints& scanPoints,
    const std::string& scanName, const RegistrationOptions& options = {});

/// Throws Error "<where>: ..." if an option is out of range for a template of that many vertices.
void checkRegistrationOptions(const RegistrationOptions& options, Eigen::Index templateVertices, const std::string& where);

/// The template's feature points: the position of each landmark vertex. Throws Error if a
/// vertex index is outside the mesh.
FeaturePoints landmarkPositions(const Mesh& templ, const std::map<std::string, int>& landmarks);

} // namespace facesketch::registration

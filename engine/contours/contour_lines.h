#pragma once
// Contour lines of one face for drawing it in a sketch-like style (thesis figure 4.9): the
// zero set of a per-vertex function, traced across each triangle as one segment between the
// two edges where it changes sign (linear interpolation along the edge), as line primitives for
// render/renderer.h. Silhouettes are the zero set of n . v; suggestive contours the zero set of
// the radial curvature k_r where D_w k_r l^2 exceeds the threshold and the surface faces the
// camera (DeCarlo et al. 2003), both with the conventions of contours/candidates.h: with the
// vertex-strength filter a segment is kept whole where both its ends pass; with rtsc's filter,
// the part of it where the test passes (as rtsc draws it). Labelled
// contours are polylines through the dataset's vertex paths.

#include "contours/candidates.h"
#include "contours/curvature.h"

#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

namespace facesketch {

struct ContourLines {
    std::vector<glm::vec3> silhouette; ///< segment endpoints, pairs
    std::vector<glm::vec3> suggestive;
    std::vector<glm::vec3> labelled;
};

/// Contour lines of `mesh` seen by `camera`. `excluded` vertices (VertexExcluded in `flags`,
/// which may be empty) drop every triangle that touches them. `labelled` holds ordered vertex
/// paths (e.g. a manifest's contours); labelled lines are kept where both ends face the camera.
ContourLines contourLines(const Mesh& mesh, const Curvature& curvature, const Camera& camera, const ContourParams& params,
    const std::vector<std::uint32_t>& flags = {}, const std::map<std::string, std::vector<int>>& labelled = {});

} // namespace facesketch

#pragma once
// Error maps of a registration (thesis 3.2.12.4, figs. 3.13-3.14 and 3.36): how far each vertex
// of a registered face lies from the scan's surface, where the scan has surface, summarised as
// mean, 95th percentile and maximum, and coloured blue (0) to red (the scale's top) for renders.

#include "core/mesh.h"

#include <glm/glm.hpp>
#include <vector>

namespace facesketch::registration {

class SurfaceQuery;

struct ErrorSummary {
    int measured = 0;  ///< vertices with a distance (not NaN)
    double mean = 0.0; ///< mm
    double p95 = 0.0;  ///< 95th percentile (nearest rank), mm
    double max = 0.0;  ///< mm
};

/// #V distances (mm) from each row of V to the surface. A vertex whose nearest point lies on the
/// surface's boundary (beside a hole or outside a face mask) is over no surface: NaN.
std::vector<double> distanceToSurface(const Vertices& V, const SurfaceQuery& surface);

/// Mean, 95th percentile and max of the finite values; `measured` 0 and zeros if there are none.
ErrorSummary summarize(const std::vector<double>& distances);

/// One RGBA colour per value: blueToRed(d / scaleMax) (render/colormap.h), mid grey for NaN.
std::vector<glm::vec4> errorColors(const std::vector<double>& distances, double scaleMax);

} // namespace facesketch::registration

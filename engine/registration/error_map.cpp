#include "registration/error_map.h"

#include "core/error.h"
#include "registration/surface_query.h"
#include "render/colormap.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facesketch::registration {

std::vector<double> distanceToSurface(const Vertices& V, const SurfaceQuery& surface)
{
    std::vector<double> out(static_cast<std::size_t>(V.rows()));
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
        const ClosestPoint c = surface.closest(V.row(i).transpose());
        // A point exactly on the boundary is still on the surface; beside it, it is not.
        out[static_cast<std::size_t>(i)] = c.onBoundary && c.distance > 1e-9 ? std::numeric_limits<double>::quiet_NaN() : c.distance;
    }
    return out;
}

ErrorSummary summarize(const std::vector<double>& distances)
{
    std::vector<double> finite;
    for (const double d : distances)
        if (std::isfinite(d))
            finite.push_back(d);
    ErrorSummary s;
    s.measured = static_cast<int>(finite.size());
    if (finite.empty())
        return s;
    std::sort(finite.begin(), finite.end());
    double sum = 0.0;
    for (const double d : finite)
        sum += d;
    s.mean = sum / static_cast<double>(finite.size());
    const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(finite.size())));
    s.p95 = finite[std::max<std::size_t>(rank, 1) - 1];
    s.max = finite.back();
    return s;
}

std::vector<glm::vec4> errorColors(const std::vector<double>& distances, double scaleMax)
{
    if (!(scaleMax > 0.0))
        fail("error map: colour scale top ", scaleMax, " must be positive");
    std::vector<glm::vec4> out;
    out.reserve(distances.size());
    for (const double d : distances)
        out.push_back(std::isfinite(d) ? blueToRed(d / scaleMax) : glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    return out;
}

} // namespace facesketch::registration

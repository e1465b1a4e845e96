#pragma once
// Stroke projection (thesis 4.1.1): densify a stroke where its points are sparse, then give
// every point a depth by casting it onto a surface (sketch/stroke.h Surface): the current face
// (points that miss it take the depth interpolated along the stroke from those that hit), the
// front axis plane, the profile axis plane, or the paper plane facing the camera, each through
// the face's centre (the centre of its bounding box).
//
// Screen coordinates are pixels (x right, y down, Camera::project); world coordinates mm.

#include "core/mesh.h"
#include "geometry/camera.h"
#include "sketch/stroke.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace facesketch::sketch {

/// The world point that `camera` shows at pixel (x, y) with depth `depth` in [0, 1] (the
/// inverse of Camera::project).
Eigen::Vector3d unproject(const Camera& camera, double x, double y, double depth);

/// Adds points on a cardinal spline (tension `tension` in [0, 1]: 0 is Catmull-Rom, 1 straight
/// lines) between consecutive points more than `maxGapPx` apart, so that no gap exceeds it.
/// Segments with an end outside `limit` (x0, y0, x1, y1; far off screen) are left as they are,
/// so a wild point cannot make millions of points. `source`, if given, receives for each output
/// point the index of the input point at or before it. Throws Error for maxGapPx <= 0.
std::vector<Eigen::Vector2d> densify(const std::vector<Eigen::Vector2d>& points, double maxGapPx, double tension,
    const Eigen::Vector4d& limit, std::vector<int>* source = nullptr);

struct ProjectedStroke {
    std::vector<Eigen::Vector2d> screen; ///< densified points, pixels
    std::vector<Eigen::Vector3d> world;  ///< the same points with their depth, mm
    std::vector<int> source;             ///< per point: the stroke point at or before it
    std::vector<char> hit;               ///< Surface::Face: the point's ray met the face
    int hits = 0;                        ///< how many did
    /// Surface::Face with no hit: every point was cast onto the paper plane instead (the stroke
    /// lies wholly off the face, e.g. a silhouette drawn just outside it).
    bool fellBackToPaper = false;
};

/// Densifies (maxGapPx, tension as densify(); the limit is the viewport widened by its size on
/// every side) and projects the stroke's points in `camera` onto `stroke.surface` of `face`.
/// Throws Error if a plane is seen edge-on (e.g. the front plane from the profile), naming the
/// surface and view.
ProjectedStroke projectStroke(const Stroke& stroke, const Camera& camera, const Mesh& face, double maxGapPx, double tension);

} // namespace facesketch::sketch

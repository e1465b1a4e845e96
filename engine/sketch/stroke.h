#pragma once
// A stroke as the user drew it (thesis 4.1.1): 2D screen points in one view, with everything
// needed to replay it exactly. Pixels, origin at the viewport's top-left corner, x right, y down
// (the same convention as Camera::project). The view is stored as an OrbitView, so
// orbitCamera(stroke.view) is the identical camera wherever and whenever the stroke is replayed.

#include "geometry/camera.h"

#include <optional>
#include <string>
#include <vector>

namespace facesketch::sketch {

struct StrokePoint {
    double x = 0; ///< pixels from the left edge
    double y = 0; ///< pixels from the top edge
    /// Milliseconds since the stroke began, when the input device reported it.
    std::optional<double> timeMs;
};

/// What a stroke point is cast onto to give it a depth (thesis 4.1.1, fig. 4.2).
enum class Surface {
    Face,         ///< (a) the current face; points that miss it take depth interpolated from those that hit
    FrontPlane,   ///< (b) the plane through the face's centre facing +z
    ProfilePlane, ///< (c) the plane through the face's centre facing +x
    Paper,        ///< (d) the plane through the face's centre facing the camera
};

/// "face", "front-plane", "profile-plane", "paper"; parseSurface throws Error naming other text.
const char* surfaceName(Surface surface);
Surface parseSurface(const std::string& text);

struct Stroke {
    std::vector<StrokePoint> points; ///< in drawing order
    OrbitView view;                  ///< the camera and viewport it was drawn in
    Surface surface = Surface::Face;
};

/// Throws Error naming `what` and the offending field or point (index and value) if the stroke
/// cannot be read: no points, a NaN or infinite coordinate or time, times that go backwards, or
/// a view orbitCamera rejects. A single point, points off screen and zero-length strokes are
/// valid here; mappers decide what they can read from them.
void validateStroke(const Stroke& stroke, const std::string& what);

} // namespace facesketch::sketch

#pragma once
// Colour maps for data drawn over faces: densities and errors go from blue (low) to red (high),
// as the thesis' figures 4.16-4.17 and its error renders do.

#include <glm/glm.hpp>

namespace facesketch {

/// The "jet" ramp: 0 -> blue, 0.25 -> cyan, 0.5 -> green, 0.75 -> yellow, 1 -> red; t is clamped.
glm::vec4 blueToRed(double t);

} // namespace facesketch

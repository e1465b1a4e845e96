#include "render/colormap.h"

#include <algorithm>
#include <cmath>

namespace facesketch {

glm::vec4 blueToRed(double t)
{
    static const glm::vec3 stops[5] = { { 0, 0, 1 }, { 0, 1, 1 }, { 0, 1, 0 }, { 1, 1, 0 }, { 1, 0, 0 } };
    t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 0.0;
    const double x = t * 4.0;
    const int i = std::min(static_cast<int>(x), 3);
    const float f = static_cast<float>(x - i);
    return glm::vec4(stops[i] + f * (stops[i + 1] - stops[i]), 1.0f);
}

} // namespace facesketch

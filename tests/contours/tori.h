#pragma once
// Test meshes shared by the contour tests.

#include "core/mesh.h"
#include "core/random.h"
#include "geometry/primitives.h"

#include <cmath>
#include <vector>

namespace facesketch::test {

/// Three different bumpy tori (not umbilic anywhere, curvature derivative non-zero), one
/// topology: 4,608 vertices each.
inline std::vector<Mesh> bumpyTori()
{
    std::vector<Mesh> meshes;
    Random random(11);
    for (int m = 0; m < 3; ++m) {
        Mesh t = makeTorus(30.0, 10.0 + 2 * m, 96, 48);
        const double a = random.uniform(0, 2 * M_PI), b = random.uniform(0, 2 * M_PI);
        for (Eigen::Index v = 0; v < t.V.rows(); ++v) {
            const double x = t.V(v, 0), y = t.V(v, 1);
            t.V(v, 2) *= 1.0 + 0.15 * std::sin(0.1 * x + a) * std::cos(0.08 * y + b);
        }
        meshes.push_back(t);
    }
    return meshes;
}

} // namespace facesketch::test

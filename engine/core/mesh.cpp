#include "core/mesh.h"

#include "core/error.h"

#include <cmath>

namespace facesketch {

void validateMesh(const Mesh& mesh, const std::string& what)
{
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(mesh.V(i, c)))
                fail(what, ": vertex ", i, " has non-finite coordinate ", "xyz"[c], " = ", mesh.V(i, c));
    const auto n = mesh.V.rows();
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
        for (int c = 0; c < 3; ++c)
            if (mesh.F(t, c) < 0 || mesh.F(t, c) >= n)
                fail(what, ": triangle ", t, " has vertex index ", mesh.F(t, c), " outside [0, ", n, ")");
        if (mesh.F(t, 0) == mesh.F(t, 1) || mesh.F(t, 1) == mesh.F(t, 2) || mesh.F(t, 0) == mesh.F(t, 2))
            fail(what, ": triangle ", t, " repeats a vertex (", mesh.F(t, 0), ", ", mesh.F(t, 1), ", ", mesh.F(t, 2), ")");
    }
}

} // namespace facesketch

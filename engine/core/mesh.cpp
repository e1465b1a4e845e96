#include "core/mesh.h"

#include "core/error.h"

#include <cmath>

namespace facesketch {

namespace {
void checkBatch(std::size_t floats, Eigen::Index vertexCount, std::size_t mesh)
{
    if (vertexCount < 0 || (mesh + 1) * 3 * static_cast<std::size_t>(vertexCount) > floats)
        fail("meshInBatch: no mesh ", mesh, " of ", vertexCount, " vertices in ", floats, " floats");
}
} // namespace

Eigen::Map<Eigen::VectorXd> asVector(Vertices& V)
{
    return { V.data(), V.size() };
}

Eigen::Map<const Eigen::VectorXd> asVector(const Vertices& V)
{
    return { V.data(), V.size() };
}

Eigen::Map<Vertices> asVertices(Eigen::VectorXd& x)
{
    if (x.size() % 3 != 0)
        fail("asVertices: ", x.size(), " coordinates is not a whole number of xyz vertices");
    return { x.data(), x.size() / 3, 3 };
}

Eigen::Map<const Vertices> asVertices(const Eigen::VectorXd& x)
{
    if (x.size() % 3 != 0)
        fail("asVertices: ", x.size(), " coordinates is not a whole number of xyz vertices");
    return { x.data(), x.size() / 3, 3 };
}

Eigen::Map<VerticesF> meshInBatch(std::vector<float>& meshMajor, Eigen::Index vertexCount, std::size_t mesh)
{
    checkBatch(meshMajor.size(), vertexCount, mesh);
    return { meshMajor.data() + mesh * 3 * static_cast<std::size_t>(vertexCount), vertexCount, 3 };
}

Eigen::Map<const VerticesF> meshInBatch(const std::vector<float>& meshMajor, Eigen::Index vertexCount, std::size_t mesh)
{
    checkBatch(meshMajor.size(), vertexCount, mesh);
    return { meshMajor.data() + mesh * 3 * static_cast<std::size_t>(vertexCount), vertexCount, 3 };
}

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

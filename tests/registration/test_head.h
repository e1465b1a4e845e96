#pragma once
// A small analytic "head" for the registration tests: an icosphere pushed into an ellipsoid
// with a nose, so that the cylinder about the vertical axis sees one surface everywhere except
// near the poles. Landmarks are the vertices nearest to fixed directions, so every tessellation
// of the same surface has its landmarks at nearly the same places.

#include "core/mesh.h"
#include "geometry/primitives.h"
#include "registration/feature_points.h"

#include <cmath>
#include <map>
#include <string>

namespace facesketch::test {

/// The analytic head surface as a function of the unit direction u (|u| = 1): an ellipsoid of
/// semi-axes 70 (x), 90 (y), 80 (z) mm plus a nose bump 12 mm high in front, plus `cheek` mm of
/// a bump on the face's left cheek (a feature the RBF cannot know from the landmarks).
inline Eigen::Vector3d headSurface(const Eigen::Vector3d& u, double cheek = 0.0)
{
    Eigen::Vector3d p(70.0 * u.x(), 90.0 * u.y(), 80.0 * u.z());
    const double nose = 12.0 * std::exp(-(u.x() * u.x() + (u.y() + 0.1) * (u.y() + 0.1)) / 0.02) * std::max(0.0, u.z());
    const double bump = cheek * std::exp(-((u.x() - 0.45) * (u.x() - 0.45) + (u.y() + 0.2) * (u.y() + 0.2)) / 0.03) * std::max(0.0, u.z());
    return p + (nose + bump) * u;
}

/// The head tessellated as an icosphere with `subdivisions` (3: 642 vertices, 5: 10242).
inline Mesh makeHead(int subdivisions, double cheek = 0.0)
{
    Mesh mesh = makeIcosphere(1.0, subdivisions);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
        mesh.V.row(i) = headSurface(mesh.V.row(i).transpose().normalized(), cheek).transpose();
    return mesh;
}

/// Unit directions of the landmarks on the head (the face looks down +z, +x is its left).
inline std::map<std::string, Eigen::Vector3d> landmarkDirections()
{
    std::map<std::string, Eigen::Vector3d> d;
    auto add = [&](const std::string& name, double x, double y, double z) { d[name] = Eigen::Vector3d(x, y, z).normalized(); };
    add("prn", 0.0, -0.1, 1.0);
    add("sn", 0.0, -0.3, 1.0);
    add("en_l", 0.15, 0.2, 1.0);
    add("en_r", -0.15, 0.2, 1.0);
    add("ex_l", 0.45, 0.2, 1.0);
    add("ex_r", -0.45, 0.2, 1.0);
    add("ch_l", 0.3, -0.5, 1.0);
    add("ch_r", -0.3, -0.5, 1.0);
    add("pg", 0.0, -0.85, 1.0);
    add("n", 0.0, 0.3, 1.0);
    add("ls", 0.0, -0.42, 1.0);
    add("li", 0.0, -0.6, 1.0);
    add("obs_l", 1.0, 0.1, -0.1);
    add("obs_r", -1.0, 0.1, -0.1);
    return d;
}

/// The landmark vertices of `mesh` (made by makeHead): the vertex nearest to each direction.
inline std::map<std::string, int> headLandmarks(const Mesh& mesh)
{
    std::map<std::string, int> out;
    for (const auto& [name, u] : landmarkDirections()) {
        Eigen::Index best = 0;
        (mesh.V.rowwise().normalized() * u).maxCoeff(&best);
        out[name] = static_cast<int>(best);
    }
    return out;
}

/// The landmark positions on the analytic surface itself (what a person would click on a scan).
inline registration::FeaturePoints headPoints(double cheek = 0.0)
{
    registration::FeaturePoints out;
    for (const auto& [name, u] : landmarkDirections())
        out[name] = headSurface(u, cheek);
    return out;
}

} // namespace facesketch::test

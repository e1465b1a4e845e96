#include "geometry/camera.h"

#include "core/error.h"

#include <glm/gtc/matrix_transform.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace facesketch {

ViewAngles parseView(const std::string& text)
{
    if (text == "front")
        return {0, 0};
    if (text == "profile")
        return {90, 0};
    if (text == "34")
        return {45, 0};
    const auto comma = text.find(',');
    if (comma != std::string::npos) {
        const std::string az = text.substr(0, comma), el = text.substr(comma + 1);
        char* end1 = nullptr;
        char* end2 = nullptr;
        const double a = std::strtod(az.c_str(), &end1), e = std::strtod(el.c_str(), &end2);
        if (!az.empty() && !el.empty() && *end1 == '\0' && *end2 == '\0' && std::isfinite(a) && std::isfinite(e) && std::abs(e) <= 90)
            return {a, e};
    }
    fail("view '", text, "': expected front, profile, 34 or AZ,EL in degrees with |EL| <= 90");
}

glm::dvec3 Camera::project(const glm::dvec3& world) const
{
    const glm::dvec4 clip = projection * view * glm::dvec4(world, 1.0);
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return {(ndc.x + 1.0) * 0.5 * width, (1.0 - ndc.y) * 0.5 * height, ndc.z};
}

glm::dvec3 Camera::toCamera(const glm::dvec3& world) const
{
    return kind == Projection::Orthographic ? -forward : glm::normalize(eye - world);
}

Camera frameSphere(const glm::dvec3& centre, double radius, ViewAngles angles, int width, int height, Projection kind, double margin)
{
    if (width <= 0 || height <= 0 || !(radius > 0) || !std::isfinite(radius))
        fail("frameSphere: image ", width, "x", height, " and radius ", radius, " must be positive");
    const double az = glm::radians(angles.azimuthDeg), el = glm::radians(angles.elevationDeg);
    const glm::dvec3 toEye(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
    // Straight above or below, +y is no longer a usable up vector: the face's forward is.
    const glm::dvec3 up = std::abs(angles.elevationDeg) > 89.9 ? glm::dvec3(0, 0, angles.elevationDeg > 0 ? -1 : 1) : glm::dvec3(0, 1, 0);

    Camera c;
    c.kind = kind;
    c.width = width;
    c.height = height;
    const double aspect = static_cast<double>(width) / height;
    const double halfSmall = radius * (1.0 + margin);
    const double halfW = aspect >= 1 ? halfSmall * aspect : halfSmall;
    const double halfH = aspect >= 1 ? halfSmall : halfSmall / aspect;
    double distance;
    if (kind == Projection::Orthographic) {
        distance = 3.0 * radius;
        c.projection = glm::orthoRH_ZO(-halfW, halfW, -halfH, halfH, distance - 2.0 * radius, distance + 2.0 * radius);
    } else {
        const double fovSmall = glm::radians(30.0);
        distance = halfSmall / std::sin(fovSmall / 2);
        const double fovY = aspect >= 1 ? fovSmall : 2.0 * std::atan(std::tan(fovSmall / 2) / aspect);
        c.projection = glm::perspectiveRH_ZO(fovY, aspect, std::max(distance - 2.0 * radius, distance * 0.01), distance + 2.0 * radius);
    }
    c.eye = centre + toEye * distance;
    c.forward = -toEye;
    c.view = glm::lookAtRH(c.eye, centre, up);
    return c;
}

Camera frameMesh(const Mesh& mesh, ViewAngles angles, int width, int height, Projection kind, double margin)
{
    if (mesh.V.rows() == 0)
        fail("frameMesh: the mesh has no vertices");
    const Eigen::RowVector3d lo = mesh.V.colwise().minCoeff(), hi = mesh.V.colwise().maxCoeff();
    const Eigen::RowVector3d mid = (lo + hi) / 2;
    const double radius = std::max((mesh.V.rowwise() - mid).rowwise().norm().maxCoeff(), 1e-9);
    return frameSphere({mid.x(), mid.y(), mid.z()}, radius, angles, width, height, kind, margin);
}

} // namespace facesketch

#include "geometry/camera.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>

namespace facesketch {

ViewAngles parseView(const std::string& text)
{
    if (text == "front")
        return { 0, 0 };
    if (text == "profile")
        return { 90, 0 };
    if (text == "34")
        return { 45, 0 };
    const auto comma = text.find(',');
    if (comma != std::string::npos) {
        const std::string az = text.substr(0, comma), el = text.substr(comma + 1);
        char* end1 = nullptr;
        char* end2 = nullptr;
        const double a = std::strtod(az.c_str(), &end1), e = std::strtod(el.c_str(), &end2);
        if (!az.empty() && !el.empty() && *end1 == '\0' && *end2 == '\0' && std::isfinite(a) && std::isfinite(e) && std::abs(e) <= 90)
            return { a, e };
    }
    fail("view '", text, "': expected front, profile, 34 or AZ,EL in degrees with |EL| <= 90");
}

glm::dvec3 Camera::project(const glm::dvec3& world) const
{
    const glm::dvec4 clip = projection * view * glm::dvec4(world, 1.0);
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return { (ndc.x + 1.0) * 0.5 * width, (1.0 - ndc.y) * 0.5 * height, ndc.z };
}

glm::dvec3 Camera::toCamera(const glm::dvec3& world) const
{
    return kind == Projection::Orthographic ? -forward : glm::normalize(eye - world);
}

Camera orbitCamera(const OrbitView& v)
{
    auto positive = [](double x) { return std::isfinite(x) && x > 0; };
    if (v.width <= 0 || v.height <= 0)
        fail("orbit view: viewport ", v.width, "x", v.height, " must be positive");
    if (!positive(v.distance))
        fail("orbit view: distance ", v.distance, " must be positive");
    if (!positive(v.nearPlane) || !std::isfinite(v.farPlane) || !(v.nearPlane < v.farPlane))
        fail("orbit view: near plane ", v.nearPlane, " and far plane ", v.farPlane, " must satisfy 0 < near < far");
    if (v.kind == Projection::Orthographic && !positive(v.halfHeight))
        fail("orbit view: half height ", v.halfHeight, " must be positive");
    if (v.kind == Projection::Perspective && !(positive(v.fovY) && v.fovY < 3.14))
        fail("orbit view: field of view ", v.fovY, " must be in (0, pi) radians");
    if (!std::isfinite(v.angles.azimuthDeg) || !std::isfinite(v.angles.elevationDeg) || std::abs(v.angles.elevationDeg) > 90)
        fail("orbit view: azimuth ", v.angles.azimuthDeg, " and elevation ", v.angles.elevationDeg,
            " must be finite with |elevation| <= 90");
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(v.target[i]))
            fail("orbit view: target coordinate ", i, " is ", v.target[i]);

    const double az = glm::radians(v.angles.azimuthDeg), el = glm::radians(v.angles.elevationDeg);
    const glm::dvec3 toEye(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
    // Straight above or below, +y is no longer a usable up vector: the face's forward is.
    const glm::dvec3 up
        = std::abs(v.angles.elevationDeg) > 89.9 ? glm::dvec3(0, 0, v.angles.elevationDeg > 0 ? -1 : 1) : glm::dvec3(0, 1, 0);

    Camera c;
    c.kind = v.kind;
    c.width = v.width;
    c.height = v.height;
    const double aspect = static_cast<double>(v.width) / v.height;
    if (v.kind == Projection::Orthographic) {
        const double halfW = v.halfHeight * aspect;
        c.projection = glm::orthoRH_ZO(-halfW, halfW, -v.halfHeight, v.halfHeight, v.nearPlane, v.farPlane);
    } else {
        c.projection = glm::perspectiveRH_ZO(v.fovY, aspect, v.nearPlane, v.farPlane);
    }
    c.eye = v.target + toEye * v.distance;
    c.forward = -toEye;
    c.view = glm::lookAtRH(c.eye, v.target, up);
    return c;
}

OrbitView frameSphereView(const glm::dvec3& centre, double radius, ViewAngles angles, int width, int height, Projection kind, double margin)
{
    if (width <= 0 || height <= 0 || !(radius > 0) || !std::isfinite(radius))
        fail("frameSphere: image ", width, "x", height, " and radius ", radius, " must be positive");
    OrbitView v;
    v.target = centre;
    v.angles = angles;
    v.kind = kind;
    v.width = width;
    v.height = height;
    const double aspect = static_cast<double>(width) / height;
    const double halfSmall = radius * (1.0 + margin);
    if (kind == Projection::Orthographic) {
        v.distance = 3.0 * radius;
        v.halfHeight = aspect >= 1 ? halfSmall : halfSmall / aspect;
        v.nearPlane = v.distance - 2.0 * radius;
    } else {
        const double fovSmall = glm::radians(30.0);
        v.distance = halfSmall / std::sin(fovSmall / 2);
        v.fovY = aspect >= 1 ? fovSmall : 2.0 * std::atan(std::tan(fovSmall / 2) / aspect);
        v.nearPlane = std::max(v.distance - 2.0 * radius, v.distance * 0.01);
    }
    v.farPlane = v.distance + 2.0 * radius;
    return v;
}

Camera frameSphere(const glm::dvec3& centre, double radius, ViewAngles angles, int width, int height, Projection kind, double margin)
{
    return orbitCamera(frameSphereView(centre, radius, angles, width, height, kind, margin));
}

OrbitView frameMeshView(const Mesh& mesh, ViewAngles angles, int width, int height, Projection kind, double margin)
{
    if (mesh.V.rows() == 0)
        fail("frameMesh: the mesh has no vertices");
    const Eigen::RowVector3d lo = mesh.V.colwise().minCoeff(), hi = mesh.V.colwise().maxCoeff();
    const Eigen::RowVector3d mid = (lo + hi) / 2;
    const double radius = std::max((mesh.V.rowwise() - mid).rowwise().norm().maxCoeff(), 1e-9);
    return frameSphereView({ mid.x(), mid.y(), mid.z() }, radius, angles, width, height, kind, margin);
}

Camera frameMesh(const Mesh& mesh, ViewAngles angles, int width, int height, Projection kind, double margin)
{
    return orbitCamera(frameMeshView(mesh, angles, width, height, kind, margin));
}

} // namespace facesketch

#pragma once
// Cameras for the offscreen renderer. World convention (docs/dataset-format.md): +y up, the face
// looks down +z, units mm. A view is given by azimuth and elevation in degrees: azimuth 0 looks
// at the face from the front (camera on +z), azimuth 90 from the face's left (camera on +x),
// elevation positive looks from above. Pixel (0, 0) is the top-left corner of the image.

#include "core/mesh.h"

#include <glm/glm.hpp>
#include <string>

namespace facesketch {

struct ViewAngles {
    double azimuthDeg = 0;
    double elevationDeg = 0;
};

/// Parses "front" (0,0), "profile" (90,0), "34" (three-quarter: 45,0) or "AZ,EL" in degrees.
/// Throws Error naming the text if it is none of these.
ViewAngles parseView(const std::string& text);

enum class Projection { Orthographic, Perspective };

struct Camera {
    glm::dmat4 view { 1.0 };         ///< world to eye
    glm::dmat4 projection { 1.0 };   ///< eye to clip space, z in [0, 1], y up (the viewport flips y)
    glm::dvec3 eye { 0.0 };          ///< camera position (for perspective view vectors)
    glm::dvec3 forward { 0, 0, -1 }; ///< viewing direction (for orthographic view vectors)
    Projection kind = Projection::Orthographic;
    int width = 0; ///< image size in pixels
    int height = 0;

    /// Pixel coordinates (x right, y down, pixel centres at +0.5) and depth in [0, 1].
    glm::dvec3 project(const glm::dvec3& world) const;
    /// Unit vector from a world point towards the camera (orthographic: -forward).
    glm::dvec3 toCamera(const glm::dvec3& world) const;
};

/// A camera as a user places it: orbiting a target point. It holds everything the camera is
/// made from, so a stroke stored with its OrbitView replays with the identical camera anywhere
/// (sketch/stroke.h). frameSphere and frameMesh return cameras made by orbitCamera.
struct OrbitView {
    glm::dvec3 target { 0.0 }; ///< orbit centre, mm
    ViewAngles angles;         ///< azimuth and elevation of the eye seen from the target
    double distance = 300;     ///< eye to target, mm
    Projection kind = Projection::Orthographic;
    double halfHeight = 100;          ///< orthographic: half the visible height, mm
    double fovY = 0.5235987755982988; ///< perspective: vertical field of view, radians
    double nearPlane = 1;             ///< distance of the near clipping plane from the eye, mm
    double farPlane = 1000;           ///< of the far one, mm
    int width = 0;                    ///< viewport in pixels
    int height = 0;
};

/// The camera of an orbit view. Straight above or below (|elevation| > 89.9 degrees) the up
/// vector is the face's forward axis instead of +y. Throws Error naming the field for a
/// non-positive size, distance, half height, field of view or plane, or near >= far.
Camera orbitCamera(const OrbitView& view);

/// The orbit view that frames a sphere (centre, radius) from `angles`: the sphere fills the
/// smaller image side with `margin` (fraction of the radius) to spare.
OrbitView frameSphereView(const glm::dvec3& centre, double radius, ViewAngles angles, int width, int height,
    Projection kind = Projection::Orthographic, double margin = 0.05);
/// frameSphereView around the mesh's bounding sphere (centre of the bounding box).
OrbitView frameMeshView(
    const Mesh& mesh, ViewAngles angles, int width, int height, Projection kind = Projection::Orthographic, double margin = 0.05);

/// A camera looking at a sphere (centre, radius) from `angles`, framing it to fill the smaller
/// image side with `margin` (fraction of the radius) to spare. Orthographic: the sphere's
/// outline has radius min(width, height) / 2 / (1 + margin) pixels.
Camera frameSphere(const glm::dvec3& centre, double radius, ViewAngles angles, int width, int height,
    Projection kind = Projection::Orthographic, double margin = 0.05);
/// frameSphere around the mesh's bounding sphere (centre of the bounding box).
Camera frameMesh(
    const Mesh& mesh, ViewAngles angles, int width, int height, Projection kind = Projection::Orthographic, double margin = 0.05);

} // namespace facesketch

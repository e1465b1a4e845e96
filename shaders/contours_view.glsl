// The view block and helpers shared by contours_radial.comp.glsl and contours.comp.glsl; the
// members are CONTOURS_VIEW_MEMBERS in shared.h, the host side facesketch::shaders::ContourView.
layout(binding = CONTOURS_BINDING_VIEW, std140) uniform View { CONTOURS_VIEW_MEMBERS };

// The unit vector from p towards the camera. Arithmetic rather than a ?: on the projection:
// glslang makes a branch of that, and lavapipe runs both sides of it for every row (4 ms of a
// whole view).
vec3 toCamera(vec3 p)
{
    return normalize(eye.xyz - p * eye.w);
}

// Pixel position (x, y; (0, 0) top-left) and depth in [0, 1] of a world point.
vec3 project(vec3 p)
{
    vec4 clip = viewProjection * vec4(p, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    return vec3((ndc.x + 1.0) * 0.5 * screen.x, (1.0 - ndc.y) * 0.5 * screen.y, ndc.z);
}

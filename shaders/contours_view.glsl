// The view block and helpers shared by contours_radial.comp.glsl and contours.comp.glsl; the
// host side is ContourViewGpu in engine/contours/candidates_gpu.cpp.
layout(binding = CONTOURS_BINDING_VIEW, std140) uniform View {
    mat4 viewProjection;
    vec4 eye;        // perspective: the eye, 1; orthographic: the unit vector towards the camera, 0
    vec4 rect;       // x0, y0, x1, y1 in pixels
    vec4 sphere;     // centre, radius in mm
    vec4 thresholds; // silhouette, suggestive, featureSize^2, 0
    vec4 screen;     // width, height
    uvec4 counts;    // vertexCount, meshCount, capacity, listed vertices
};

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

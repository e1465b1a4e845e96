// The view block and helpers shared by contours_radial.comp.glsl and contours.comp.glsl; the
// host side is ContourViewGpu in engine/contours/candidates_gpu.cpp.
layout(binding = CONTOURS_BINDING_VIEW, std140) uniform View {
    mat4 viewProjection;
    vec4 eye;        // xyz; w = 1 for perspective, 0 for orthographic
    vec4 toCameraOrtho;
    vec4 rect;       // x0, y0, x1, y1 in pixels
    vec4 sphere;     // centre, radius in mm
    vec4 thresholds; // silhouette, suggestive, featureSize^2, 0
    vec4 screen;     // width, height
    uvec4 counts;    // vertexCount, meshCount, capacity, listed vertices
};

vec3 toCamera(vec3 p)
{
    return eye.w > 0.5 ? normalize(eye.xyz - p) : toCameraOrtho.xyz;
}

// Pixel position (x, y; (0, 0) top-left) and depth in [0, 1] of a world point.
vec3 project(vec3 p)
{
    vec4 clip = viewProjection * vec4(p, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    return vec3((ndc.x + 1.0) * 0.5 * screen.x, (1.0 - ndc.y) * 0.5 * screen.y, ndc.z);
}

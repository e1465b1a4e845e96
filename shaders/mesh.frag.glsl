#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared.h"

layout(push_constant) uniform Constants { DRAW_CONSTANTS_MEMBERS };

// The pipeline's DRAW_MODE_* (the push constant `mode` holds the same value). A constant, so that
// the triangles' shader compiles without the points' discard: a shader that may discard makes
// lavapipe test depth after shading every fragment instead of before.
layout(constant_id = 0) const uint kMode = DRAW_MODE_LIT;

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec4 outColor;

void main()
{
    if (kMode == DRAW_MODE_POINTS) {
        vec2 d = gl_PointCoord * 2.0 - 1.0;
        if (dot(d, d) > 1.0)
            discard;
        outColor = inColor;
        return;
    }
    if (kMode == DRAW_MODE_UNLIT) {
        outColor = inColor;
        return;
    }
    // Two-sided: open meshes (faces are open at the back) show their inside lit, not black.
    vec3 n = normalize(inNormal);
    if (!gl_FrontFacing)
        n = -n;
    vec3 l = normalize(toLight.xyz);
    float diffuse = max(dot(n, l), 0.0);
    // Head light: half vector == light. x^40 = x^32 x^8 by squaring, cheaper than pow's exp and log
    // in a software rasteriser.
    float s2 = diffuse * diffuse, s4 = s2 * s2, s8 = s4 * s4, s16 = s8 * s8;
    float specular = s16 * s16 * s8;
    vec3 rgb = inColor.rgb * (0.22 + 0.78 * diffuse) + vec3(0.12 * specular);
    outColor = vec4(min(rgb, vec3(1.0)), inColor.a);
}

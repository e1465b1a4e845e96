#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared.h"

layout(push_constant) uniform Constants { DRAW_CONSTANTS_MEMBERS };

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec4 outColor;

void main()
{
    if (mode == DRAW_MODE_POINTS) {
        vec2 d = gl_PointCoord * 2.0 - 1.0;
        if (dot(d, d) > 1.0)
            discard;
        outColor = inColor;
        return;
    }
    if (mode == DRAW_MODE_UNLIT) {
        outColor = inColor;
        return;
    }
    // Two-sided: open meshes (faces are open at the back) show their inside lit, not black.
    vec3 n = normalize(inNormal);
    if (!gl_FrontFacing)
        n = -n;
    vec3 l = normalize(toLight.xyz);
    float diffuse = max(dot(n, l), 0.0);
    float specular = pow(max(dot(n, l), 0.0), 40.0); // head light: half vector == light
    vec3 rgb = inColor.rgb * (0.22 + 0.78 * diffuse) + vec3(0.12 * specular);
    outColor = vec4(min(rgb, vec3(1.0)), inColor.a);
}

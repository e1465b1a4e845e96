#version 450
#extension GL_GOOGLE_include_directive : require
// Shared by triangles, lines and points: world-space position, normal and colour.
#include "shared.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inColor;

layout(push_constant) uniform Constants { DRAW_CONSTANTS_MEMBERS };

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec4 outColor;

void main()
{
    gl_Position = viewProjection * vec4(inPosition, 1.0);
    gl_Position.z -= depthOffset * gl_Position.w;
    gl_PointSize = pointSize;
    outNormal = inNormal;
    outColor = inColor;
}

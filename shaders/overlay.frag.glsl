#version 450
#extension GL_GOOGLE_include_directive : require
// The full-viewport overlay (SceneRenderer::setOverlay): an RGBA8 image in a texel buffer,
// stretched over the viewport with the nearest texel, row 0 at the top; blended by alpha.
#include "shared.h"

layout(binding = 0) uniform samplerBuffer overlay;

layout(push_constant) uniform Constants { OVERLAY_CONSTANTS_MEMBERS };

layout(location = 0) out vec4 outColor;

void main()
{
    // gl_FragCoord is in framebuffer pixels, origin at the top-left, centres at +0.5.
    uvec2 texel = min(uvec2(gl_FragCoord.xy / vec2(targetWidth, targetHeight) * vec2(imageWidth, imageHeight)),
        uvec2(imageWidth - 1, imageHeight - 1));
    outColor = texelFetch(overlay, int(texel.y * imageWidth + texel.x));
}

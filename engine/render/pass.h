#pragma once
// The pass a window draws a SceneRenderer into with dynamic rendering: a depth image and, with
// MSAA, a multisampled colour image of the window's size, resolved into the swapchain image.
//
//   PassTargets targets = createPassTargets(device, scene.target(), frame.extent);
//   // per frame (after FrameLoop::beginFrame); on a new frame.extent, hand the old targets to
//   // FrameLoop::defer and create new ones
//   beginPass(device, frame.cmd, targets, frame.image, frame.view, { 1, 1, 1, 1 });
//   scene.record(frame.cmd, frame.slot, camera, frame.extent);
//   endPass(device, frame.cmd, frame.image, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
//
// The depth and MSAA images are written and read only inside the pass, and their contents are
// not kept between passes, so one set serves every frame in flight.

#include "gpu/buffers.h"
#include "render/scene_renderer.h"

namespace facesketch {

struct PassTargets {
    gpu::Image color; ///< multisampled colour (only when format.samples > 1), resolved into the output
    gpu::Image depth;
    VkExtent2D extent {}; ///< pixels
    RenderTargetFormat format;
};

/// Targets of `extent` pixels (each side 1..16384) for `format` (dynamic rendering: its
/// renderPass must be null). Throws Error on a bad size or a render-pass format.
PassTargets createPassTargets(gpu::Device& device, const RenderTargetFormat& format, VkExtent2D extent);
void destroyPassTargets(gpu::Device& device, PassTargets& targets);

/// Records the layout transitions and vkCmdBeginRendering: `output` (an image of
/// targets.format.color and targets.extent, e.g. the swapchain image, its old contents dropped)
/// is cleared to `clear` (RGBA as written), depth to 1. With MSAA the samples are averaged into
/// `output` at endPass. Needs Device::beginRendering.
void beginPass(gpu::Device& device, VkCommandBuffer cmd, PassTargets& targets, VkImage output, VkImageView outputView, glm::vec4 clear);
/// Ends rendering and moves `output` from COLOR_ATTACHMENT_OPTIMAL to `finalLayout`:
/// PRESENT_SRC_KHR to present, TRANSFER_SRC_OPTIMAL to copy it (a screenshot), or
/// COLOR_ATTACHMENT_OPTIMAL to leave it for another pass (e.g. ImGui's render pass, which loads it).
void endPass(gpu::Device& device, VkCommandBuffer cmd, VkImage output, VkImageLayout finalLayout);

} // namespace facesketch

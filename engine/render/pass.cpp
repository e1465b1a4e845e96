#include "render/pass.h"

#include "core/error.h"
#include "gpu/swapchain.h"

namespace facesketch {

PassTargets createPassTargets(gpu::Device& device, const RenderTargetFormat& format, VkExtent2D extent)
{
    if (extent.width < 1 || extent.height < 1 || extent.width > 16384 || extent.height > 16384)
        fail("createPassTargets: size ", extent.width, "x", extent.height, " must be within 1..16384");
    if (format.renderPass)
        fail("createPassTargets: the format names a render pass; pass targets are for dynamic rendering");
    if (format.samples != 1 && format.samples != 4)
        fail("createPassTargets: samples must be 1 or 4, not ", format.samples);
    PassTargets t;
    t.extent = extent;
    t.format = format;
    const auto samples = format.samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
    t.depth = gpu::createImage(
        device, extent.width, extent.height, format.depth, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, samples);
    if (format.samples > 1) {
        try {
            t.color = gpu::createImage(device, extent.width, extent.height, format.color,
                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT, VK_IMAGE_ASPECT_COLOR_BIT, samples);
        } catch (...) {
            gpu::destroyImage(device, t.depth);
            throw;
        }
    }
    return t;
}

void destroyPassTargets(gpu::Device& device, PassTargets& t)
{
    if (t.color.image)
        gpu::destroyImage(device, t.color);
    if (t.depth.image)
        gpu::destroyImage(device, t.depth);
    t = PassTargets {};
}

void beginPass(gpu::Device& device, VkCommandBuffer cmd, PassTargets& t, VkImage output, VkImageView outputView, glm::vec4 clear)
{
    if (!device.beginRendering)
        fail("beginPass: device ", device.name, " has no dynamic rendering");
    const bool msaa = t.color.image != VK_NULL_HANDLE;
    // The previous frame's use of the shared depth / MSAA images (attachment writes) finishes
    // before this frame's clears: the barriers order them, the old contents are dropped.
    gpu::imageBarrier(cmd, output, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
        VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    if (msaa)
        gpu::imageBarrier(cmd, t.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    const VkPipelineStageFlags depthStages = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    gpu::imageBarrier(cmd, t.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
        VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, depthStages, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, depthStages,
        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);

    auto color = gpu::makeStruct<VkRenderingAttachmentInfoKHR>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO_KHR);
    color.imageView = msaa ? t.color.view : outputView;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
    color.clearValue.color = { { clear.r, clear.g, clear.b, clear.a } };
    if (msaa) {
        color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        color.resolveImageView = outputView;
        color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    }
    auto depth = gpu::makeStruct<VkRenderingAttachmentInfoKHR>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO_KHR);
    depth.imageView = t.depth.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = { 1.0f, 0 };

    auto info = gpu::makeStruct<VkRenderingInfoKHR>(VK_STRUCTURE_TYPE_RENDERING_INFO_KHR);
    info.renderArea = { { 0, 0 }, t.extent };
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    info.pDepthAttachment = &depth;
    device.beginRendering(cmd, &info);
}

void endPass(gpu::Device& device, VkCommandBuffer cmd, VkImage output, VkImageLayout finalLayout)
{
    device.endRendering(cmd);
    if (finalLayout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL)
        return;
    VkPipelineStageFlags dstStage = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
    VkAccessFlags dstAccess = 0;
    if (finalLayout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL) {
        dstStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        dstAccess = VK_ACCESS_TRANSFER_READ_BIT;
    }
    gpu::imageBarrier(cmd, output, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, finalLayout,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, dstStage, dstAccess);
}

} // namespace facesketch

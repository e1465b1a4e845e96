#include "render/renderer.h"

#include "core/error.h"
#include "gpu/buffers.h"
#include "gpu/compute.h"

#include <cstring>

namespace facesketch {

namespace {

constexpr VkFormat colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;

} // namespace

struct Renderer::Impl {
    gpu::Device& device;
    int width, height;
    VkSampleCountFlagBits samples;
    gpu::Image color, depth, resolve; // resolve only with MSAA
    VkRenderPass renderPass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    gpu::Buffer readback;
    std::unique_ptr<SceneRenderer> scene;

    Impl(gpu::Device& d, int w, int h, int s)
        : device(d)
        , width(w)
        , height(h)
    {
        if (w <= 0 || h <= 0 || w > 16384 || h > 16384)
            fail("Renderer: image size ", w, "x", h, " must be within 1..16384");
        if (s != 1 && s != 4)
            fail("Renderer: samples must be 1 or 4, not ", s);
        samples = s == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
        createTargets();
        // One slot: render() waits for each submission before the next edit can land.
        scene = std::make_unique<SceneRenderer>(device,
            RenderTargetFormat { .color = colorFormat, .depth = depthFormat, .samples = s, .renderPass = renderPass, .subpass = 0 }, 1);
        readback = gpu::createBuffer(device, VkDeviceSize(w) * h * 4, 0, gpu::MemoryUse::Readback);
    }

    ~Impl()
    {
        // Every submission was waited for by render(): nothing is in flight.
        scene.reset();
        gpu::destroyBuffer(device, readback);
        vkDestroyFramebuffer(device.device, framebuffer, nullptr);
        vkDestroyRenderPass(device.device, renderPass, nullptr);
        if (resolve.image)
            gpu::destroyImage(device, resolve);
        gpu::destroyImage(device, depth);
        gpu::destroyImage(device, color);
    }

    bool msaa() const { return samples != VK_SAMPLE_COUNT_1_BIT; }
    const gpu::Image& output() const { return msaa() ? resolve : color; }

    void createTargets()
    {
        const auto w = static_cast<std::uint32_t>(width), h = static_cast<std::uint32_t>(height);
        const VkImageUsageFlags colorUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (msaa() ? 0 : VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        color = gpu::createImage(device, w, h, colorFormat, colorUsage, VK_IMAGE_ASPECT_COLOR_BIT, samples);
        depth
            = gpu::createImage(device, w, h, depthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, samples);
        if (msaa())
            resolve = gpu::createImage(device, w, h, colorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                VK_IMAGE_ASPECT_COLOR_BIT);

        VkAttachmentDescription attachments[3] = {};
        attachments[0].format = colorFormat;
        attachments[0].samples = samples;
        attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        attachments[0].storeOp = msaa() ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
        attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        attachments[0].finalLayout = msaa() ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        attachments[1] = attachments[0];
        attachments[1].format = depthFormat;
        attachments[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        attachments[2] = attachments[0];
        attachments[2].samples = VK_SAMPLE_COUNT_1_BIT;
        attachments[2].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        attachments[2].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        attachments[2].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;

        VkAttachmentReference colorRef { 0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL };
        VkAttachmentReference depthRef { 1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL };
        VkAttachmentReference resolveRef { 2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL };
        VkSubpassDescription subpass {};
        subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subpass.colorAttachmentCount = 1;
        subpass.pColorAttachments = &colorRef;
        subpass.pDepthStencilAttachment = &depthRef;
        subpass.pResolveAttachments = msaa() ? &resolveRef : nullptr;

        // The copy to the readback buffer waits for the attachment writes to finish.
        VkSubpassDependency dependency {};
        dependency.srcSubpass = 0;
        dependency.dstSubpass = VK_SUBPASS_EXTERNAL;
        dependency.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        dependency.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        dependency.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
        dependency.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;

        auto info = gpu::makeStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
        info.attachmentCount = msaa() ? 3 : 2;
        info.pAttachments = attachments;
        info.subpassCount = 1;
        info.pSubpasses = &subpass;
        info.dependencyCount = 1;
        info.pDependencies = &dependency;
        VK_CHECK(vkCreateRenderPass(device.device, &info, nullptr, &renderPass));

        VkImageView views[3] = { color.view, depth.view, msaa() ? resolve.view : VK_NULL_HANDLE };
        auto fb = gpu::makeStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
        fb.renderPass = renderPass;
        fb.attachmentCount = msaa() ? 3 : 2;
        fb.pAttachments = views;
        fb.width = w;
        fb.height = h;
        fb.layers = 1;
        VK_CHECK(vkCreateFramebuffer(device.device, &fb, nullptr, &framebuffer));
    }
};

Renderer::Renderer(gpu::Device& device, int width, int height, int samples)
    : impl_(std::make_unique<Impl>(device, width, height, samples))
{
}
Renderer::~Renderer() = default;

int Renderer::width() const
{
    return impl_->width;
}
int Renderer::height() const
{
    return impl_->height;
}

SceneRenderer& Renderer::scene()
{
    return *impl_->scene;
}

void Renderer::addMesh(const Mesh& mesh, const MeshStyle& style, const std::vector<glm::vec4>& colors)
{
    validateMesh(mesh, "Renderer::addMesh");
    if (!colors.empty() && colors.size() != static_cast<size_t>(mesh.V.rows()))
        fail("Renderer::addMesh: ", colors.size(), " colours for ", mesh.V.rows(), " vertices");
    impl_->scene->addMesh(mesh, style, colors);
}

void Renderer::addLines(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors)
{
    if (points.size() % 2 != 0)
        fail("Renderer::addLines: ", points.size(), " points do not pair up into segments");
    impl_->scene->addLines(points, colors);
}

void Renderer::addPoints(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors, float size)
{
    if (!(size > 0))
        fail("Renderer::addPoints: point size ", size, " must be positive");
    impl_->scene->addPoints(points, colors, size);
}

void Renderer::clear()
{
    impl_->scene->clear();
}

Image Renderer::render(const Camera& camera, glm::vec4 background)
{
    auto& im = *impl_;
    if (camera.width != im.width || camera.height != im.height)
        fail("Renderer::render: camera is ", camera.width, "x", camera.height, " but the target is ", im.width, "x", im.height);
    const VkExtent2D extent { std::uint32_t(im.width), std::uint32_t(im.height) };

    // submitAndWait waits on the fence of this submission alone.
    gpu::submitAndWait(im.device, [&](VkCommandBuffer cmd) {
        VkClearValue clears[3] = {};
        clears[0].color = { { background.r, background.g, background.b, background.a } };
        clears[1].depthStencil = { 1.0f, 0 };
        auto begin = gpu::makeStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
        begin.renderPass = im.renderPass;
        begin.framebuffer = im.framebuffer;
        begin.renderArea = { { 0, 0 }, extent };
        begin.clearValueCount = im.msaa() ? 3 : 2;
        begin.pClearValues = clears;
        vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
        im.scene->record(cmd, 0, camera, extent);
        vkCmdEndRenderPass(cmd);

        VkBufferImageCopy region {};
        region.imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 };
        region.imageExtent = { extent.width, extent.height, 1 };
        vkCmdCopyImageToBuffer(cmd, im.output().image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, im.readback.buffer, 1, &region);
        gpu::hostReadBarrier(cmd);
    });

    Image image;
    image.width = im.width;
    image.height = im.height;
    image.pixels.resize(static_cast<size_t>(im.width) * im.height * 4);
    // Readback memory is host-coherent and mapped (MemoryUse::Readback).
    std::memcpy(image.pixels.data(), im.readback.mapped, image.pixels.size());
    return image;
}

} // namespace facesketch

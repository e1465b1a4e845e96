#include "render/renderer.h"

#include "core/error.h"
#include "geometry/normals.h"
#include "gpu/buffers.h"
#include "gpu/compute.h"
#include "shaders/mesh_frag.h"
#include "shaders/mesh_vert.h"
#include "shaders/shared.h"

#include <array>
#include <cmath>
#include <cstring>

namespace facesketch {

namespace {

struct DrawVertex {
    float position[3];
    float normal[3];
    float color[4];
};

struct alignas(16) DrawConstants {
    glm::mat4 viewProjection;
    glm::vec4 toLight;
    std::uint32_t mode;
    float pointSize;
    float depthOffset;
    float padding;
};

enum Topology { TriangleList = 0, LineList = 1, PointList = 2, TopologyCount = 3 };

struct DrawItem {
    Topology topology;
    std::uint32_t mode;
    float pointSize;
    std::uint32_t firstVertex, vertexCount; // into the shared vertex array
    std::uint32_t firstIndex, indexCount;   // triangles only
};

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
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::array<VkPipeline, TopologyCount> pipelines {};
    gpu::Buffer readback;

    std::vector<DrawVertex> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<DrawItem> items;

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
        createPipelines();
        readback = gpu::createBuffer(device, VkDeviceSize(w) * h * 4, 0, gpu::MemoryUse::Readback);
    }

    ~Impl()
    {
        vkDeviceWaitIdle(device.device);
        gpu::destroyBuffer(device, readback);
        for (VkPipeline p : pipelines)
            vkDestroyPipeline(device.device, p, nullptr);
        vkDestroyPipelineLayout(device.device, layout, nullptr);
        vkDestroyShaderModule(device.device, frag, nullptr);
        vkDestroyShaderModule(device.device, vert, nullptr);
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

    void createPipelines()
    {
        vert = gpu::createShaderModule(device, gpu::shaderCode(mesh_vert));
        frag = gpu::createShaderModule(device, gpu::shaderCode(mesh_frag));
        VkPushConstantRange range { VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawConstants) };
        auto layoutInfo = gpu::makeStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
        layoutInfo.pushConstantRangeCount = 1;
        layoutInfo.pPushConstantRanges = &range;
        VK_CHECK(vkCreatePipelineLayout(device.device, &layoutInfo, nullptr, &layout));

        VkPipelineShaderStageCreateInfo stages[2]
            = { gpu::makeStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO),
                  gpu::makeStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO) };
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = vert;
        stages[0].pName = "main";
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = frag;
        stages[1].pName = "main";

        VkVertexInputBindingDescription binding { 0, sizeof(DrawVertex), VK_VERTEX_INPUT_RATE_VERTEX };
        VkVertexInputAttributeDescription attributes[3] = { { 0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(DrawVertex, position) },
            { 1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(DrawVertex, normal) },
            { 2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(DrawVertex, color) } };
        auto vertexInput = gpu::makeStruct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
        vertexInput.vertexBindingDescriptionCount = 1;
        vertexInput.pVertexBindingDescriptions = &binding;
        vertexInput.vertexAttributeDescriptionCount = 3;
        vertexInput.pVertexAttributeDescriptions = attributes;

        // Negative height: +y up in clip space comes out as row 0 at the top of the image.
        VkViewport viewport { 0, float(height), float(width), -float(height), 0, 1 };
        VkRect2D scissor { { 0, 0 }, { std::uint32_t(width), std::uint32_t(height) } };
        auto viewportState = gpu::makeStruct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
        viewportState.viewportCount = 1;
        viewportState.pViewports = &viewport;
        viewportState.scissorCount = 1;
        viewportState.pScissors = &scissor;

        auto raster = gpu::makeStruct<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = VK_CULL_MODE_NONE;
        // Facing is decided in framebuffer space, where the negative-height viewport has already
        // undone the y flip of the framebuffer's y-down axis: counter-clockwise stays front.
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;

        auto multisample = gpu::makeStruct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
        multisample.rasterizationSamples = samples;

        auto depthState
            = gpu::makeStruct<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
        depthState.depthTestEnable = VK_TRUE;
        depthState.depthWriteEnable = VK_TRUE;
        depthState.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;

        VkPipelineColorBlendAttachmentState blendAttachment {};
        blendAttachment.blendEnable = VK_TRUE;
        blendAttachment.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
        blendAttachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blendAttachment.colorBlendOp = VK_BLEND_OP_ADD;
        blendAttachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blendAttachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blendAttachment.alphaBlendOp = VK_BLEND_OP_ADD;
        blendAttachment.colorWriteMask = 0xf;
        auto blend = gpu::makeStruct<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
        blend.attachmentCount = 1;
        blend.pAttachments = &blendAttachment;

        const VkPrimitiveTopology topologies[TopologyCount]
            = { VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, VK_PRIMITIVE_TOPOLOGY_POINT_LIST };
        for (int t = 0; t < TopologyCount; ++t) {
            auto assembly
                = gpu::makeStruct<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
            assembly.topology = topologies[t];
            auto info = gpu::makeStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
            info.stageCount = 2;
            info.pStages = stages;
            info.pVertexInputState = &vertexInput;
            info.pInputAssemblyState = &assembly;
            info.pViewportState = &viewportState;
            info.pRasterizationState = &raster;
            info.pMultisampleState = &multisample;
            info.pDepthStencilState = &depthState;
            info.pColorBlendState = &blend;
            info.layout = layout;
            info.renderPass = renderPass;
            VK_CHECK(vkCreateGraphicsPipelines(device.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipelines[t]));
        }
    }

    void addVertices(
        Topology topology, std::uint32_t mode, float pointSize, const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors)
    {
        if (colors.size() != 1 && colors.size() != points.size())
            fail("Renderer: ", colors.size(), " colours for ", points.size(), " points (give one, or one per point)");
        DrawItem item { topology, mode, pointSize, static_cast<std::uint32_t>(vertices.size()), static_cast<std::uint32_t>(points.size()),
            0, 0 };
        for (size_t i = 0; i < points.size(); ++i) {
            const glm::vec4& c = colors.size() == 1 ? colors[0] : colors[i];
            if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) || !std::isfinite(points[i].z))
                fail("Renderer: point ", i, " is not finite");
            vertices.push_back({ { points[i].x, points[i].y, points[i].z }, { 0, 0, 0 }, { c.r, c.g, c.b, c.a } });
        }
        items.push_back(item);
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

void Renderer::addMesh(const Mesh& mesh, const MeshStyle& style, const std::vector<glm::vec4>& colors)
{
    validateMesh(mesh, "Renderer::addMesh");
    if (!colors.empty() && colors.size() != static_cast<size_t>(mesh.V.rows()))
        fail("Renderer::addMesh: ", colors.size(), " colours for ", mesh.V.rows(), " vertices");
    const Vertices N = vertexNormals(mesh);
    auto& im = *impl_;
    DrawItem item { TriangleList, style.lit ? std::uint32_t(DRAW_MODE_LIT) : std::uint32_t(DRAW_MODE_UNLIT), 1.0f,
        static_cast<std::uint32_t>(im.vertices.size()), static_cast<std::uint32_t>(mesh.V.rows()),
        static_cast<std::uint32_t>(im.indices.size()), static_cast<std::uint32_t>(mesh.F.size()) };
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
        const glm::vec4 c = colors.empty() ? style.color : colors[v];
        im.vertices.push_back({ { float(mesh.V(v, 0)), float(mesh.V(v, 1)), float(mesh.V(v, 2)) },
            { float(N(v, 0)), float(N(v, 1)), float(N(v, 2)) }, { c.r, c.g, c.b, c.a } });
    }
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
        for (int k = 0; k < 3; ++k)
            im.indices.push_back(static_cast<std::uint32_t>(mesh.F(t, k)));
    im.items.push_back(item);
}

void Renderer::addLines(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors)
{
    if (points.size() % 2 != 0)
        fail("Renderer::addLines: ", points.size(), " points do not pair up into segments");
    impl_->addVertices(LineList, DRAW_MODE_UNLIT, 1.0f, points, colors);
}

void Renderer::addPoints(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors, float size)
{
    if (!(size > 0))
        fail("Renderer::addPoints: point size ", size, " must be positive");
    // Without the largePoints feature only 1-pixel points are valid.
    impl_->addVertices(PointList, DRAW_MODE_POINTS, impl_->device.largePoints ? size : 1.0f, points, colors);
}

void Renderer::clear()
{
    impl_->vertices.clear();
    impl_->indices.clear();
    impl_->items.clear();
}

Image Renderer::render(const Camera& camera, glm::vec4 background)
{
    auto& im = *impl_;
    if (camera.width != im.width || camera.height != im.height)
        fail("Renderer::render: camera is ", camera.width, "x", camera.height, " but the target is ", im.width, "x", im.height);
    gpu::Device& device = im.device;

    gpu::Buffer vertexBuffer, indexBuffer;
    if (!im.vertices.empty()) {
        vertexBuffer = gpu::createBuffer(device, im.vertices.size() * sizeof(DrawVertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        gpu::uploadBuffer(device, vertexBuffer, im.vertices.data(), vertexBuffer.size);
    }
    if (!im.indices.empty()) {
        indexBuffer = gpu::createBuffer(device, im.indices.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        gpu::uploadBuffer(device, indexBuffer, im.indices.data(), indexBuffer.size);
    }

    const glm::mat4 viewProjection = glm::mat4(camera.projection * camera.view);
    // Head light: from the camera, raised a little so that the nose casts shading downwards.
    const glm::dvec3 right
        = glm::normalize(glm::cross(camera.forward, glm::dvec3(camera.view[0][1], camera.view[1][1], camera.view[2][1])));
    const glm::dvec3 up = glm::cross(right, camera.forward);
    const glm::vec3 toLight = glm::normalize(glm::vec3(-camera.forward + 0.35 * up + 0.15 * right));

    gpu::submitAndWait(device, [&](VkCommandBuffer cmd) {
        VkClearValue clears[3] = {};
        clears[0].color = { { background.r, background.g, background.b, background.a } };
        clears[1].depthStencil = { 1.0f, 0 };
        auto begin = gpu::makeStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
        begin.renderPass = im.renderPass;
        begin.framebuffer = im.framebuffer;
        begin.renderArea = { { 0, 0 }, { std::uint32_t(im.width), std::uint32_t(im.height) } };
        begin.clearValueCount = im.msaa() ? 3 : 2;
        begin.pClearValues = clears;
        vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
        if (vertexBuffer.buffer) {
            const VkDeviceSize zero = 0;
            vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer.buffer, &zero);
            if (indexBuffer.buffer)
                vkCmdBindIndexBuffer(cmd, indexBuffer.buffer, 0, VK_INDEX_TYPE_UINT32);
        }
        for (const DrawItem& item : im.items) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, im.pipelines[item.topology]);
            DrawConstants constants { viewProjection, glm::vec4(toLight, 0), item.mode, item.pointSize,
                item.topology == TriangleList ? 0.0f : 2e-4f, 0.0f };
            vkCmdPushConstants(cmd, im.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(constants), &constants);
            if (item.topology == TriangleList)
                vkCmdDrawIndexed(cmd, item.indexCount, 1, item.firstIndex, static_cast<std::int32_t>(item.firstVertex), 0);
            else
                vkCmdDraw(cmd, item.vertexCount, 1, item.firstVertex, 0);
        }
        vkCmdEndRenderPass(cmd);

        VkBufferImageCopy region {};
        region.imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 };
        region.imageExtent = { std::uint32_t(im.width), std::uint32_t(im.height), 1 };
        vkCmdCopyImageToBuffer(cmd, im.output().image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, im.readback.buffer, 1, &region);
        gpu::hostReadBarrier(cmd);
    });

    Image image;
    image.width = im.width;
    image.height = im.height;
    image.pixels.resize(static_cast<size_t>(im.width) * im.height * 4);
    gpu::readbackBuffer(device, im.readback, image.pixels.data(), image.pixels.size());
    if (indexBuffer.buffer)
        gpu::destroyBuffer(device, indexBuffer);
    if (vertexBuffer.buffer)
        gpu::destroyBuffer(device, vertexBuffer);
    return image;
}

} // namespace facesketch

#include "render/scene_renderer.h"

#include "core/error.h"
#include "geometry/normals.h"
#include "gpu/buffers.h"
#include "gpu/compute.h"
#include "shaders/mesh_frag.h"
#include "shaders/mesh_vert.h"
#include "shaders/overlay_frag.h"
#include "shaders/overlay_vert.h"
#include "shaders/shared.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>

namespace facesketch {

// A named namespace, not an anonymous one: SceneRenderer::Impl holds these types, and gcc's
// -Wsubobject-linkage rejects a class with anonymous-namespace members once the file is compiled
// inside a unity source (CMAKE_UNITY_BUILD, which CI uses).
namespace scene_detail {

struct DrawVertex {
    float position[3];
    float normal[3];
    float color[4];
};

using shaders::DrawConstants;
using shaders::OverlayConstants;

enum class Kind { Mesh, Lines, Points, ScreenPolyline };
enum Topology { TriangleList = 0, LineList = 1, PointList = 2, TopologyCount = 3 };

// A host-visible buffer per slot, rewritten when the item's version moved past the slot's.
struct SlotBuffer {
    gpu::Buffer buffer;
    std::uint64_t version = 0;
};

struct Item {
    Kind kind;
    bool visible = true;
    bool depthTest = true;
    std::uint32_t mode = DRAW_MODE_LIT;
    float size = 1.0f; // point size or line width, pixels
    std::vector<DrawVertex> vertices;
    std::uint64_t version = 1;
    std::vector<SlotBuffer> copies; // one per slot
    // Meshes only: the colour of the style (when no per-vertex colours) and the triangles.
    glm::vec4 styleColor {};
    bool perVertexColors = false;
    bool opaque = false; // every vertex's alpha is 1: drawn without blending (the same colours)
    Triangles faces;     // kept for the normals of updateMesh
    gpu::Buffer indices;
    std::uint32_t indexCount = 0;
};

Topology topologyOf(Kind kind)
{
    switch (kind) {
    case Kind::Mesh:
        return TriangleList;
    case Kind::Points:
        return PointList;
    default:
        return LineList;
    }
}

void checkColors(const char* what, size_t colors, size_t points)
{
    if (colors != 1 && colors != points)
        fail(what, ": ", colors, " colours for ", points, " points (give one, or one per point)");
}

std::vector<DrawVertex> pointVertices(const char* what, const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors)
{
    checkColors(what, colors.size(), points.size());
    std::vector<DrawVertex> vertices;
    vertices.reserve(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::vec4& c = colors.size() == 1 ? colors[0] : colors[i];
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) || !std::isfinite(points[i].z))
            fail(what, ": point ", i, " is not finite");
        vertices.push_back({ { points[i].x, points[i].y, points[i].z }, { 0, 0, 0 }, { c.r, c.g, c.b, c.a } });
    }
    return vertices;
}

// Segments joining consecutive points, as a line list.
std::vector<DrawVertex> polylineVertices(const std::vector<glm::vec2>& pixels, const std::vector<glm::vec4>& colors)
{
    const char* what = "SceneRenderer::addScreenPolyline";
    checkColors(what, colors.size(), pixels.size());
    std::vector<DrawVertex> vertices;
    for (size_t i = 0; i + 1 < pixels.size(); ++i)
        for (size_t k : { i, i + 1 }) {
            const glm::vec4& c = colors.size() == 1 ? colors[0] : colors[k];
            if (!std::isfinite(pixels[k].x) || !std::isfinite(pixels[k].y))
                fail(what, ": point ", k, " is not finite");
            vertices.push_back({ { pixels[k].x, pixels[k].y, 0.0f }, { 0, 0, 0 }, { c.r, c.g, c.b, c.a } });
        }
    return vertices;
}

} // namespace scene_detail
using namespace scene_detail;

struct SceneRenderer::Impl {
    gpu::Device& device;
    // The constructor's target (index 0) and those of addTarget().
    std::vector<RenderTargetFormat> targets;
    std::uint32_t slotCount;
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    VkShaderModule overlayVert = VK_NULL_HANDLE, overlayFrag = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout overlaySetLayout = VK_NULL_HANDLE;
    VkPipelineLayout overlayLayout = VK_NULL_HANDLE;
    // Built on first use, by pipeline()'s key, and the overlay's per target.
    std::map<std::uint32_t, VkPipeline> pipelines;
    std::map<std::uint32_t, VkPipeline> overlayPipelines;

    std::map<DrawId, Item> items; // ordered by id: the order added
    DrawId nextId = 1;

    // The overlay image, and per slot a texel buffer holding its copy.
    Image overlay;
    bool hasOverlay = false;
    std::uint64_t overlayVersion = 1;
    struct OverlayCopy {
        gpu::Buffer buffer;
        gpu::TexelView view;
        std::uint64_t version = 0;
    };
    std::vector<OverlayCopy> overlayCopies;

    // Removed GPU data, destroyed when every slot in `pending` has been recorded again.
    struct Retired {
        std::uint32_t pending; // bit per slot
        std::vector<gpu::Buffer> buffers;
        std::vector<gpu::TexelView> views;
    };
    std::vector<Retired> retired;

    Impl(gpu::Device& d, const RenderTargetFormat& t, std::uint32_t s)
        : device(d)
        , slotCount(s)
    {
        checkTarget(t);
        if (s < 1 || s > 8)
            fail("SceneRenderer: slots must be within 1..8, not ", s);
        targets.push_back(t);
        overlayCopies.resize(s);
        vert = gpu::createShaderModule(device, gpu::shaderCode(mesh_vert));
        frag = gpu::createShaderModule(device, gpu::shaderCode(mesh_frag));
        overlayVert = gpu::createShaderModule(device, gpu::shaderCode(overlay_vert));
        overlayFrag = gpu::createShaderModule(device, gpu::shaderCode(overlay_frag));

        VkPushConstantRange range { VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawConstants) };
        auto layoutInfo = gpu::makeStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
        layoutInfo.pushConstantRangeCount = 1;
        layoutInfo.pPushConstantRanges = &range;
        VK_CHECK(vkCreatePipelineLayout(device.device, &layoutInfo, nullptr, &layout));

        VkDescriptorSetLayoutBinding binding { 0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr };
        auto setInfo = gpu::makeStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
        setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
        setInfo.bindingCount = 1;
        setInfo.pBindings = &binding;
        VK_CHECK(vkCreateDescriptorSetLayout(device.device, &setInfo, nullptr, &overlaySetLayout));
        VkPushConstantRange overlayRange { VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(OverlayConstants) };
        auto overlayInfo = gpu::makeStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
        overlayInfo.setLayoutCount = 1;
        overlayInfo.pSetLayouts = &overlaySetLayout;
        overlayInfo.pushConstantRangeCount = 1;
        overlayInfo.pPushConstantRanges = &overlayRange;
        VK_CHECK(vkCreatePipelineLayout(device.device, &overlayInfo, nullptr, &overlayLayout));
    }

    ~Impl()
    {
        for (auto& [id, item] : items)
            destroyItem(item);
        for (OverlayCopy& copy : overlayCopies)
            destroyOverlayCopy(copy);
        for (Retired& r : retired)
            destroyRetired(r);
        for (auto& [key, p] : pipelines)
            vkDestroyPipeline(device.device, p, nullptr);
        for (auto& [key, p] : overlayPipelines)
            vkDestroyPipeline(device.device, p, nullptr);
        vkDestroyPipelineLayout(device.device, overlayLayout, nullptr);
        vkDestroyDescriptorSetLayout(device.device, overlaySetLayout, nullptr);
        vkDestroyPipelineLayout(device.device, layout, nullptr);
        for (VkShaderModule m : { overlayFrag, overlayVert, frag, vert })
            vkDestroyShaderModule(device.device, m, nullptr);
    }

    void destroyItem(Item& item)
    {
        for (SlotBuffer& copy : item.copies)
            if (copy.buffer.buffer)
                gpu::destroyBuffer(device, copy.buffer);
        if (item.indices.buffer)
            gpu::destroyBuffer(device, item.indices);
    }

    void destroyOverlayCopy(OverlayCopy& copy)
    {
        if (copy.view.view)
            gpu::destroyTexelView(device, copy.view);
        if (copy.buffer.buffer)
            gpu::destroyBuffer(device, copy.buffer);
        copy = OverlayCopy {};
    }

    void destroyRetired(Retired& r)
    {
        for (gpu::TexelView& v : r.views)
            gpu::destroyTexelView(device, v);
        for (gpu::Buffer& b : r.buffers)
            gpu::destroyBuffer(device, b);
    }

    std::uint32_t allSlots() const { return slotCount == 32 ? ~0u : (1u << slotCount) - 1; }

    void retireItem(Item& item)
    {
        Retired r { allSlots(), {}, {} };
        for (SlotBuffer& copy : item.copies)
            if (copy.buffer.buffer)
                r.buffers.push_back(copy.buffer);
        if (item.indices.buffer)
            r.buffers.push_back(item.indices);
        if (!r.buffers.empty())
            retired.push_back(std::move(r));
    }

    void retireOverlayCopy(OverlayCopy& copy)
    {
        Retired r { allSlots(), {}, {} };
        if (copy.view.view)
            r.views.push_back(copy.view);
        if (copy.buffer.buffer)
            r.buffers.push_back(copy.buffer);
        if (!r.buffers.empty())
            retired.push_back(std::move(r));
        copy = OverlayCopy {};
    }

    Item& find(DrawId id, const char* what)
    {
        auto it = items.find(id);
        if (it == items.end())
            fail(what, ": no draw item ", id);
        return it->second;
    }

    DrawId add(Item item)
    {
        item.copies.resize(slotCount);
        const DrawId id = nextId++;
        items.emplace(id, std::move(item));
        return id;
    }

    // One pipeline per topology, depth test, DRAW_MODE_* (the fragment shader's specialisation)
    // and blending; opaque meshes are drawn without blending, which saves lavapipe reading back
    // every covered sample.
    // (and per target).
    VkPipeline pipeline(std::uint32_t target, Topology topology, bool depthTest, std::uint32_t mode, bool blend)
    {
        const std::uint32_t key = (target << 16) | (std::uint32_t(topology) << 8) | (mode << 2) | (depthTest ? 2u : 0u) | (blend ? 1u : 0u);
        VkPipeline& slot = pipelines[key];
        if (!slot)
            slot = createPipeline(targets[target], topology, depthTest, false, mode, blend);
        return slot;
    }

    void checkTarget(const RenderTargetFormat& t) const
    {
        if (t.samples != 1 && t.samples != 4)
            fail("SceneRenderer: samples must be 1 or 4, not ", t.samples);
        if (!t.renderPass && !device.beginRendering)
            fail("SceneRenderer: device ", device.name, " has no dynamic rendering; give a render pass in RenderTargetFormat");
    }

    VkPipeline createPipeline(const RenderTargetFormat& target, Topology topology, bool depthTest, bool overlayPass,
        std::uint32_t mode = DRAW_MODE_LIT, bool blended = true)
    {
        const VkSpecializationMapEntry modeEntry { 0, 0, sizeof(std::uint32_t) };
        VkSpecializationInfo specialization { 1, &modeEntry, sizeof(mode), &mode };
        VkPipelineShaderStageCreateInfo stages[2]
            = { gpu::makeStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO),
                  gpu::makeStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO) };
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = overlayPass ? overlayVert : vert;
        stages[0].pName = "main";
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = overlayPass ? overlayFrag : frag;
        stages[1].pName = "main";
        stages[1].pSpecializationInfo = overlayPass ? nullptr : &specialization;

        VkVertexInputBindingDescription binding { 0, sizeof(DrawVertex), VK_VERTEX_INPUT_RATE_VERTEX };
        VkVertexInputAttributeDescription attributes[3] = { { 0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(DrawVertex, position) },
            { 1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(DrawVertex, normal) },
            { 2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(DrawVertex, color) } };
        auto vertexInput = gpu::makeStruct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
        if (!overlayPass) {
            vertexInput.vertexBindingDescriptionCount = 1;
            vertexInput.pVertexBindingDescriptions = &binding;
            vertexInput.vertexAttributeDescriptionCount = 3;
            vertexInput.pVertexAttributeDescriptions = attributes;
        }

        const VkPrimitiveTopology topologies[TopologyCount]
            = { VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, VK_PRIMITIVE_TOPOLOGY_POINT_LIST };
        auto assembly
            = gpu::makeStruct<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
        assembly.topology = topologies[topology];

        auto viewportState = gpu::makeStruct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
        viewportState.viewportCount = 1;
        viewportState.scissorCount = 1;

        auto raster = gpu::makeStruct<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = VK_CULL_MODE_NONE;
        // Facing is decided in framebuffer space, where the negative-height viewport has already
        // undone the y flip of the framebuffer's y-down axis: counter-clockwise stays front.
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;

        auto multisample = gpu::makeStruct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
        multisample.rasterizationSamples = target.samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;

        auto depthState
            = gpu::makeStruct<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
        depthState.depthTestEnable = depthTest ? VK_TRUE : VK_FALSE;
        depthState.depthWriteEnable = depthTest ? VK_TRUE : VK_FALSE;
        depthState.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;

        VkPipelineColorBlendAttachmentState blendAttachment {};
        blendAttachment.blendEnable = blended ? VK_TRUE : VK_FALSE;
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

        std::vector<VkDynamicState> dynamicStates { VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR };
        if (topology == LineList && !overlayPass)
            dynamicStates.push_back(VK_DYNAMIC_STATE_LINE_WIDTH);
        auto dynamic = gpu::makeStruct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
        dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamicStates.size());
        dynamic.pDynamicStates = dynamicStates.data();

        auto rendering = gpu::makeStruct<VkPipelineRenderingCreateInfoKHR>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO_KHR);
        rendering.colorAttachmentCount = 1;
        rendering.pColorAttachmentFormats = &target.color;
        rendering.depthAttachmentFormat = target.depth;

        auto info = gpu::makeStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
        info.pNext = target.renderPass ? nullptr : &rendering;
        info.stageCount = 2;
        info.pStages = stages;
        info.pVertexInputState = &vertexInput;
        info.pInputAssemblyState = &assembly;
        info.pViewportState = &viewportState;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pDepthStencilState = &depthState;
        info.pColorBlendState = &blend;
        info.pDynamicState = &dynamic;
        info.layout = overlayPass ? overlayLayout : layout;
        info.renderPass = target.renderPass;
        info.subpass = target.subpass;
        VkPipeline p;
        VK_CHECK(vkCreateGraphicsPipelines(device.device, VK_NULL_HANDLE, 1, &info, nullptr, &p));
        return p;
    }

    // Brings the slot's copy of `item` up to date by a host write (the slot's last frame is done).
    void refresh(Item& item, std::uint32_t slot)
    {
        SlotBuffer& copy = item.copies[slot];
        if (copy.version == item.version || item.vertices.empty())
            return;
        const VkDeviceSize bytes = item.vertices.size() * sizeof(DrawVertex);
        if (copy.buffer.buffer && copy.buffer.size < bytes)
            gpu::destroyBuffer(device, copy.buffer); // the slot's frame is done with it
        if (!copy.buffer.buffer)
            copy.buffer = gpu::createBuffer(device, bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, gpu::MemoryUse::Upload);
        std::memcpy(copy.buffer.mapped, item.vertices.data(), bytes);
        copy.version = item.version;
    }

    void refreshOverlay(std::uint32_t slot)
    {
        OverlayCopy& copy = overlayCopies[slot];
        if (copy.version == overlayVersion)
            return;
        const VkDeviceSize bytes = overlay.pixels.size();
        if (copy.buffer.buffer && copy.buffer.size != bytes)
            destroyOverlayCopy(copy);
        if (!copy.buffer.buffer) {
            copy.buffer = gpu::createBuffer(device, bytes, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, gpu::MemoryUse::Upload);
            copy.view = gpu::createTexelView(device, copy.buffer, VK_FORMAT_R8G8B8A8_UNORM);
        }
        std::memcpy(copy.buffer.mapped, overlay.pixels.data(), bytes);
        copy.version = overlayVersion;
    }
};

SceneRenderer::SceneRenderer(gpu::Device& device, const RenderTargetFormat& target, std::uint32_t slots)
    : impl_(std::make_unique<Impl>(device, target, slots))
{
}
SceneRenderer::~SceneRenderer() = default;

std::uint32_t SceneRenderer::addTarget(const RenderTargetFormat& target)
{
    impl_->checkTarget(target);
    impl_->targets.push_back(target);
    return static_cast<std::uint32_t>(impl_->targets.size() - 1);
}

const RenderTargetFormat& SceneRenderer::target() const
{
    return impl_->targets.front();
}
std::uint32_t SceneRenderer::slots() const
{
    return impl_->slotCount;
}

namespace {

// Positions and normals; the colours stay.
void writeMeshVertices(Item& item, const Vertices& V, const Vertices& N)
{
    item.vertices.resize(static_cast<size_t>(V.rows()));
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
        DrawVertex& d = item.vertices[v];
        for (int k = 0; k < 3; ++k) {
            d.position[k] = float(V(v, k));
            d.normal[k] = float(N(v, k));
        }
    }
}

void paintMesh(Item& item, const std::vector<glm::vec4>& colors)
{
    item.perVertexColors = !colors.empty();
    item.opaque = true;
    for (size_t v = 0; v < item.vertices.size(); ++v) {
        const glm::vec4 c = colors.empty() ? item.styleColor : colors[v];
        float* d = item.vertices[v].color;
        d[0] = c.r, d[1] = c.g, d[2] = c.b, d[3] = c.a;
        item.opaque = item.opaque && c.a == 1.0f;
    }
}

} // namespace

DrawId SceneRenderer::addMesh(const Mesh& mesh, const MeshStyle& style, const std::vector<glm::vec4>& colors)
{
    validateMesh(mesh, "SceneRenderer::addMesh");
    if (!colors.empty() && colors.size() != static_cast<size_t>(mesh.V.rows()))
        fail("SceneRenderer::addMesh: ", colors.size(), " colours for ", mesh.V.rows(), " vertices");
    Item item;
    item.kind = Kind::Mesh;
    item.mode = style.lit ? std::uint32_t(DRAW_MODE_LIT) : std::uint32_t(DRAW_MODE_UNLIT);
    item.styleColor = style.color;
    writeMeshVertices(item, mesh.V, vertexNormals(mesh));
    item.faces = mesh.F;
    paintMesh(item, colors);
    std::vector<std::uint32_t> indices;
    indices.reserve(static_cast<size_t>(mesh.F.size()));
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
        for (int k = 0; k < 3; ++k)
            indices.push_back(static_cast<std::uint32_t>(mesh.F(t, k)));
    item.indexCount = static_cast<std::uint32_t>(indices.size());
    if (!indices.empty()) {
        item.indices = gpu::createBuffer(impl_->device, indices.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        try {
            gpu::uploadBuffer(impl_->device, item.indices, indices.data(), item.indices.size);
        } catch (...) {
            gpu::destroyBuffer(impl_->device, item.indices);
            throw;
        }
    }
    return impl_->add(std::move(item));
}

void SceneRenderer::updateMesh(DrawId id, const Vertices& V)
{
    Item& item = impl_->find(id, "SceneRenderer::updateMesh");
    if (item.kind != Kind::Mesh)
        fail("SceneRenderer::updateMesh: draw item ", id, " is not a mesh");
    if (static_cast<size_t>(V.rows()) != item.vertices.size())
        fail("SceneRenderer::updateMesh: ", V.rows(), " vertices for a mesh of ", item.vertices.size());
    if (!V.allFinite())
        fail("SceneRenderer::updateMesh: a vertex position is not finite");
    Mesh mesh;
    mesh.V = V;
    mesh.F = item.faces;
    writeMeshVertices(item, V, vertexNormals(mesh));
    ++item.version;
}

void SceneRenderer::setMeshColors(DrawId id, const std::vector<glm::vec4>& colors)
{
    Item& item = impl_->find(id, "SceneRenderer::setMeshColors");
    if (item.kind != Kind::Mesh)
        fail("SceneRenderer::setMeshColors: draw item ", id, " is not a mesh");
    if (!colors.empty() && colors.size() != item.vertices.size())
        fail("SceneRenderer::setMeshColors: ", colors.size(), " colours for ", item.vertices.size(), " vertices");
    paintMesh(item, colors);
    ++item.version;
}

void SceneRenderer::setMeshStyle(DrawId id, const MeshStyle& style)
{
    Item& item = impl_->find(id, "SceneRenderer::setMeshStyle");
    if (item.kind != Kind::Mesh)
        fail("SceneRenderer::setMeshStyle: draw item ", id, " is not a mesh");
    item.mode = style.lit ? std::uint32_t(DRAW_MODE_LIT) : std::uint32_t(DRAW_MODE_UNLIT);
    item.styleColor = style.color;
    if (!item.perVertexColors) {
        paintMesh(item, {});
        ++item.version;
    }
}

DrawId SceneRenderer::addLines(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors, const LineStyle& style)
{
    if (points.size() % 2 != 0)
        fail("SceneRenderer::addLines: ", points.size(), " points do not pair up into segments");
    if (!(style.width > 0))
        fail("SceneRenderer::addLines: line width ", style.width, " must be positive");
    Item item;
    item.kind = Kind::Lines;
    item.mode = DRAW_MODE_UNLIT;
    item.depthTest = style.depthTest;
    item.size = style.width;
    item.vertices = pointVertices("SceneRenderer::addLines", points, colors);
    return impl_->add(std::move(item));
}

DrawId SceneRenderer::addPoints(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors, float size)
{
    if (!(size > 0))
        fail("SceneRenderer::addPoints: point size ", size, " must be positive");
    Item item;
    item.kind = Kind::Points;
    item.mode = DRAW_MODE_POINTS;
    // Without the largePoints feature only 1-pixel points are valid.
    item.size = impl_->device.largePoints ? size : 1.0f;
    item.vertices = pointVertices("SceneRenderer::addPoints", points, colors);
    return impl_->add(std::move(item));
}

DrawId SceneRenderer::addScreenPolyline(const std::vector<glm::vec2>& pixels, const std::vector<glm::vec4>& colors, float width)
{
    if (!(width > 0))
        fail("SceneRenderer::addScreenPolyline: line width ", width, " must be positive");
    Item item;
    item.kind = Kind::ScreenPolyline;
    item.mode = DRAW_MODE_UNLIT;
    item.depthTest = false;
    item.size = width;
    item.vertices = polylineVertices(pixels, colors);
    return impl_->add(std::move(item));
}

void SceneRenderer::setLines(DrawId id, const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors)
{
    Item& item = impl_->find(id, "SceneRenderer::setLines");
    if (item.kind != Kind::Lines)
        fail("SceneRenderer::setLines: draw item ", id, " is not lines");
    if (points.size() % 2 != 0)
        fail("SceneRenderer::setLines: ", points.size(), " points do not pair up into segments");
    item.vertices = pointVertices("SceneRenderer::setLines", points, colors);
    ++item.version;
}

void SceneRenderer::setPoints(DrawId id, const std::vector<glm::vec3>& positions, const std::vector<glm::vec4>& colors)
{
    Item& item = impl_->find(id, "SceneRenderer::setPoints");
    if (item.kind != Kind::Points)
        fail("SceneRenderer::setPoints: draw item ", id, " is not points");
    item.vertices = pointVertices("SceneRenderer::setPoints", positions, colors);
    ++item.version;
}

void SceneRenderer::setScreenPolyline(DrawId id, const std::vector<glm::vec2>& pixels, const std::vector<glm::vec4>& colors)
{
    Item& item = impl_->find(id, "SceneRenderer::setScreenPolyline");
    if (item.kind != Kind::ScreenPolyline)
        fail("SceneRenderer::setScreenPolyline: draw item ", id, " is not a screen polyline");
    item.vertices = polylineVertices(pixels, colors);
    ++item.version;
}

void SceneRenderer::setOverlay(const Image& rgba)
{
    if (rgba.width <= 0 || rgba.height <= 0 || rgba.pixels.size() != static_cast<size_t>(rgba.width) * rgba.height * 4)
        fail("SceneRenderer::setOverlay: image of ", rgba.width, "x", rgba.height, " with ", rgba.pixels.size(), " bytes is not RGBA");
    const VkDeviceSize texels = static_cast<VkDeviceSize>(rgba.width) * rgba.height;
    if (texels > impl_->device.properties.limits.maxTexelBufferElements)
        fail("SceneRenderer::setOverlay: ", rgba.width, "x", rgba.height, " exceeds the device's ",
            impl_->device.properties.limits.maxTexelBufferElements, " texels");
    auto& im = *impl_;
    // A copy of another size is replaced; one of the same size is rewritten at the next record.
    if (!im.hasOverlay || im.overlay.width != rgba.width || im.overlay.height != rgba.height)
        for (auto& copy : im.overlayCopies)
            im.retireOverlayCopy(copy);
    im.overlay = rgba;
    im.hasOverlay = true;
    ++im.overlayVersion;
}

void SceneRenderer::clearOverlay()
{
    auto& im = *impl_;
    for (auto& copy : im.overlayCopies)
        im.retireOverlayCopy(copy);
    im.overlay = Image {};
    im.hasOverlay = false;
    ++im.overlayVersion;
}

void SceneRenderer::setVisible(DrawId id, bool visible)
{
    impl_->find(id, "SceneRenderer::setVisible").visible = visible;
}

void SceneRenderer::remove(DrawId id)
{
    Item& item = impl_->find(id, "SceneRenderer::remove");
    impl_->retireItem(item);
    impl_->items.erase(id);
}

void SceneRenderer::clear()
{
    for (auto& [id, item] : impl_->items)
        impl_->retireItem(item);
    impl_->items.clear();
    clearOverlay();
}

void SceneRenderer::record(
    VkCommandBuffer cmd, std::uint32_t slot, const Camera& camera, VkExtent2D extent, float pixelScale, std::uint32_t target)
{
    auto& im = *impl_;
    if (slot >= im.slotCount)
        fail("SceneRenderer::record: slot ", slot, " of ", im.slotCount);
    if (extent.width == 0 || extent.height == 0)
        fail("SceneRenderer::record: empty extent ", extent.width, "x", extent.height);
    if (!(pixelScale > 0 && pixelScale <= 1))
        fail("SceneRenderer::record: pixel scale ", pixelScale, " must be in (0, 1]");
    if (target >= im.targets.size())
        fail("SceneRenderer::record: target ", target, " of ", im.targets.size());

    // The slot's previous frame is done: what waited for it may go.
    for (auto it = im.retired.begin(); it != im.retired.end();) {
        it->pending &= ~(1u << slot);
        if (it->pending == 0) {
            im.destroyRetired(*it);
            it = im.retired.erase(it);
        } else
            ++it;
    }

    // Negative height: +y up in clip space comes out as row 0 at the top of the image.
    const VkViewport viewport { 0, float(extent.height), float(extent.width), -float(extent.height), 0, 1 };
    const VkRect2D scissor { { 0, 0 }, extent };
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);

    const glm::mat4 viewProjection = glm::mat4(camera.projection * camera.view);
    // Head light: from the camera, raised a little so that the nose casts shading downwards.
    const glm::dvec3 right
        = glm::normalize(glm::cross(camera.forward, glm::dvec3(camera.view[0][1], camera.view[1][1], camera.view[2][1])));
    const glm::dvec3 up = glm::cross(right, camera.forward);
    const glm::vec4 toLight(glm::normalize(glm::vec3(-camera.forward + 0.35 * up + 0.15 * right)), 0.0f);
    // Pixels (x right, y down) to clip space: the viewport's y flip puts clip +1 at row 0.
    glm::mat4 pixelsToClip(1.0f);
    pixelsToClip[0][0] = 2.0f * pixelScale / float(extent.width);
    pixelsToClip[1][1] = -2.0f * pixelScale / float(extent.height);
    pixelsToClip[3][0] = -1.0f;
    pixelsToClip[3][1] = 1.0f;

    const float maxLineWidth = im.device.wideLines ? im.device.properties.limits.lineWidthRange[1] : 1.0f;
    auto draw = [&](Item& item) {
        im.refresh(item, slot);
        const Topology topology = topologyOf(item.kind);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, im.pipeline(target, topology, item.depthTest, item.mode, !item.opaque));
        if (topology == LineList)
            vkCmdSetLineWidth(cmd, std::clamp(item.size * pixelScale, 1.0f, maxLineWidth));
        const bool screen = item.kind == Kind::ScreenPolyline;
        DrawConstants constants { screen ? pixelsToClip : viewProjection, toLight, item.mode,
            topology == PointList ? std::max(item.size * pixelScale, std::min(item.size, 1.0f)) : 1.0f,
            topology == TriangleList || screen ? 0.0f : 2e-4f };
        vkCmdPushConstants(cmd, im.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(constants), &constants);
        const VkDeviceSize zero = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &item.copies[slot].buffer.buffer, &zero);
        if (topology == TriangleList) {
            vkCmdBindIndexBuffer(cmd, item.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexed(cmd, item.indexCount, 1, 0, 0, 0);
        } else
            vkCmdDraw(cmd, static_cast<std::uint32_t>(item.vertices.size()), 1, 0, 0);
    };
    auto drawable
        = [](const Item& item) { return item.visible && !item.vertices.empty() && (item.kind != Kind::Mesh || item.indexCount > 0); };

    for (auto& [id, item] : im.items)
        if (item.depthTest && drawable(item))
            draw(item);

    if (im.hasOverlay) {
        im.refreshOverlay(slot);
        VkPipeline& overlayPipeline = im.overlayPipelines[target];
        if (!overlayPipeline)
            overlayPipeline = im.createPipeline(im.targets[target], TriangleList, false, true);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, overlayPipeline);
        auto write = gpu::makeStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        write.dstBinding = 0;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        write.pTexelBufferView = &im.overlayCopies[slot].view.view;
        im.device.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, im.overlayLayout, 0, 1, &write);
        OverlayConstants constants { std::uint32_t(im.overlay.width), std::uint32_t(im.overlay.height), float(extent.width),
            float(extent.height) };
        vkCmdPushConstants(cmd, im.overlayLayout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(constants), &constants);
        vkCmdDraw(cmd, 3, 1, 0, 0); // one triangle covering the viewport
    }

    for (auto& [id, item] : im.items)
        if (!item.depthTest && drawable(item))
            draw(item);
}

} // namespace facesketch

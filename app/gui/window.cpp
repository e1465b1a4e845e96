#include "gui/window.h"

#include "core/error.h"
#include "gpu/buffers.h"
#include "gui/x11_shm_sink.h"

#define GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace facesketch::gui {

namespace {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

void checkImgui(VkResult r)
{
    if (r != VK_SUCCESS)
        gpu::gpuFail("ImGui Vulkan backend", r);
}

} // namespace

struct Window::Targets {
    gpu::Image color; ///< MSAA colour (samples 4 only)
    gpu::Image depth;
    std::vector<VkFramebuffer> framebuffers;   ///< the scene's pass, per swapchain image
    std::vector<VkFramebuffer> uiFramebuffers; ///< ImGui's pass, per swapchain image
    gpu::Buffer readback;                      ///< screenshots
    VkExtent2D extent {};
    // The reduced-resolution scene (begin() with a scale below 1), made when first needed.
    gpu::Image reducedDepth;
    gpu::Image reduced; ///< colour, one sample per pixel
    VkFramebuffer reducedFramebuffer = VK_NULL_HANDLE;
    VkExtent2D reducedExtent {};
};

Window::Window(const WindowOptions& options)
    : samples_(options.samples)
{
    if (samples_ != 1 && samples_ != 4)
        fail("gui: samples must be 1 or 4, got ", samples_);
    if (!glfwInit())
        fail("gui: cannot initialise GLFW (no display? set DISPLAY or run under xvfb-run)");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        fail("gui: GLFW finds no Vulkan loader");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        fail("gui: cannot open a ", options.width, "x", options.height, " window");
    }
    try {
        std::uint32_t count = 0;
        const char** names = glfwGetRequiredInstanceExtensions(&count);
        gpu::InstanceOptions io;
        io.extensions.assign(names, names + count);
        instance_ = gpu::createInstance(io);
        if (glfwCreateWindowSurface(instance_.instance, window_, nullptr, &surface_) != VK_SUCCESS)
            fail("gui: cannot create a Vulkan surface for the window");
        gpu::LogicalDeviceOptions lo;
        lo.swapchain = true;
        device_ = gpu::createDevice(instance_, gpu::choosePhysicalDevice(instance_, surface_), lo);
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        createLoop(options.present, { std::uint32_t(w), std::uint32_t(h) });
        // Scaling a reduced scene up into the frame's image needs it as a blit destination and
        // linear filtering of its format (lavapipe has both; without them every frame is full size).
        VkFormatProperties fp {};
        vkGetPhysicalDeviceFormatProperties(device_.physical, colorFormat(), &fp);
        const VkFormatFeatureFlags blit
            = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
        canReduce_ = (loop_->swapchain().usage & VK_IMAGE_USAGE_TRANSFER_DST_BIT) && (fp.optimalTilingFeatures & blit) == blit;

        // The scene's pass: colour (MSAA resolved into a one-sample image, or that image itself)
        // and depth. The one-sample image is the swapchain image, or while the view moves the
        // reduced-resolution target that end() scales up into it (same pass, other framebuffer).
        const VkSampleCountFlagBits samples = samples_ == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
        std::vector<VkAttachmentDescription> att;
        VkAttachmentDescription color {};
        color.format = colorFormat();
        color.samples = samples;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        color.storeOp = samples_ == 4 ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
        color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        att.push_back(color);
        VkAttachmentDescription depth = color;
        depth.format = kDepthFormat;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        att.push_back(depth);
        if (samples_ == 4) {
            VkAttachmentDescription resolve = color;
            resolve.samples = VK_SAMPLE_COUNT_1_BIT;
            resolve.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
            resolve.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            att.push_back(resolve);
        }
        VkAttachmentReference colorRef { 0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL };
        VkAttachmentReference depthRef { 1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL };
        VkAttachmentReference resolveRef { 2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL };
        VkSubpassDescription subpass {};
        subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subpass.colorAttachmentCount = 1;
        subpass.pColorAttachments = &colorRef;
        subpass.pDepthStencilAttachment = &depthRef;
        subpass.pResolveAttachments = samples_ == 4 ? &resolveRef : nullptr;
        // The previous frame's use of the shared MSAA, depth and reduced images (its writes, and
        // end()'s blit reading the reduced image) and the acquire semaphore's wait at colour
        // output come before this frame's writes.
        VkSubpassDependency dep {};
        dep.srcSubpass = VK_SUBPASS_EXTERNAL;
        dep.dstSubpass = 0;
        dep.srcStageMask
            = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
        dep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
        dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
        dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT
            | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
        auto rp = gpu::makeStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
        rp.attachmentCount = static_cast<std::uint32_t>(att.size());
        rp.pAttachments = att.data();
        rp.subpassCount = 1;
        rp.pSubpasses = &subpass;
        rp.dependencyCount = 1;
        rp.pDependencies = &dep;
        VK_CHECK(vkCreateRenderPass(device_.device, &rp, nullptr, &renderPass_));
        // The reduced scene's pass: one sample per pixel, its colour stored for end()'s blit.
        // Antialiasing a picture that is moving and scaled up costs more than it shows.
        VkAttachmentDescription reduced[2] = { color, depth };
        reduced[0].samples = reduced[1].samples = VK_SAMPLE_COUNT_1_BIT;
        reduced[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        subpass.pResolveAttachments = nullptr;
        rp.attachmentCount = 2;
        rp.pAttachments = reduced;
        VK_CHECK(vkCreateRenderPass(device_.device, &rp, nullptr, &reducedPass_));

        // ImGui's pass: the swapchain image as the scene left it (loaded), one sample per pixel
        // (its widgets are antialiased by their own geometry), presented after.
        VkAttachmentDescription ui = color;
        ui.samples = VK_SAMPLE_COUNT_1_BIT;
        ui.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
        ui.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        ui.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        ui.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        VkAttachmentReference uiRef { 0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL };
        VkSubpassDescription uiSubpass {};
        uiSubpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        uiSubpass.colorAttachmentCount = 1;
        uiSubpass.pColorAttachments = &uiRef;
        // The scene's resolve or end()'s blit into the image come before ImGui's blending.
        VkSubpassDependency uiDep {};
        uiDep.srcSubpass = VK_SUBPASS_EXTERNAL;
        uiDep.dstSubpass = 0;
        uiDep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
        uiDep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        uiDep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        uiDep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        rp.attachmentCount = 1;
        rp.pAttachments = &ui;
        rp.pSubpasses = &uiSubpass;
        rp.pDependencies = &uiDep;
        VK_CHECK(vkCreateRenderPass(device_.device, &rp, nullptr, &uiPass_));

        // ImGui, scaled for the display.
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr; // no imgui.ini beside the user's files
        ImGui::StyleColorsDark();
        const float scale = static_cast<float>(contentScale());
        ImGui::GetStyle().ScaleAllSizes(scale);
        ImGui::GetIO().FontGlobalScale = scale;
        // Our callbacks see each event first and hand it on to ImGui.
        glfwSetWindowUserPointer(window_, this);
        // Positions come from the events themselves, not from glfwGetCursorPos: on X11 that asks
        // the server where the pointer is now, so when a slow frame leaves several motion events
        // queued, all of them (and the button release after them) would read the pointer's latest
        // position and a stroke drawn in that time would collapse to a point or two.
        glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int mods) {
            auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
            double x = 0, y = 0;
            self->eventCursor(x, y);
            if (self->events_.mouseButton)
                self->events_.mouseButton(button, action, mods, x, y);
            ImGui_ImplGlfw_MouseButtonCallback(w, button, action, mods);
        });
        glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double screenX, double screenY) {
            auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
            const double s = self->contentScale();
            self->lastEvent_ = { screenX * s, screenY * s };
            if (self->events_.cursor)
                self->events_.cursor(self->lastEvent_->x, self->lastEvent_->y);
        });
        glfwSetScrollCallback(window_, [](GLFWwindow* w, double dx, double dy) {
            auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
            if (self->events_.scroll)
                self->events_.scroll(dy);
            ImGui_ImplGlfw_ScrollCallback(w, dx, dy);
        });
        glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
            auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
            if (self->events_.key)
                self->events_.key(key, action, mods);
            ImGui_ImplGlfw_KeyCallback(w, key, scancode, action, mods);
        });
        glfwSetCharCallback(window_, ImGui_ImplGlfw_CharCallback);
        glfwSetWindowFocusCallback(window_, ImGui_ImplGlfw_WindowFocusCallback);
        glfwSetCursorEnterCallback(window_, ImGui_ImplGlfw_CursorEnterCallback);
        imguiGlfw_ = ImGui_ImplGlfw_InitForVulkan(window_, false);
        VkDescriptorPoolSize poolSize { VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16 };
        auto pool = gpu::makeStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
        pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
        pool.maxSets = 16;
        pool.poolSizeCount = 1;
        pool.pPoolSizes = &poolSize;
        VK_CHECK(vkCreateDescriptorPool(device_.device, &pool, nullptr, &imguiPool_));
        ImGui_ImplVulkan_InitInfo info {};
        info.Instance = instance_.instance;
        info.PhysicalDevice = device_.physical;
        info.Device = device_.device;
        info.QueueFamily = device_.queueFamily;
        info.Queue = device_.queue;
        info.DescriptorPool = imguiPool_;
        info.Subpass = 0;
        const auto images = static_cast<std::uint32_t>(std::max<size_t>(loop_->swapchain().images.size(), 2));
        info.MinImageCount = 2;
        // ImGui keeps a ring of vertex buffers this long; at least the frames in flight.
        info.ImageCount = std::max(images, gpu::framesInFlight);
        info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
        info.CheckVkResultFn = checkImgui;
        imguiVulkan_ = ImGui_ImplVulkan_Init(&info, uiPass_);
        gpu::submitAndWait(device_, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
        ImGui_ImplVulkan_DestroyFontUploadObjects();
    } catch (...) {
        release();
        throw;
    }
}

Window::~Window()
{
    release();
}

void Window::release()
{
    if (loop_)
        loop_->waitFrames();
    if (ImGui::GetCurrentContext()) {
        if (imguiFrame_)
            ImGui::EndFrame();
        imguiFrame_ = false;
        if (imguiVulkan_)
            ImGui_ImplVulkan_Shutdown();
        if (imguiGlfw_)
            ImGui_ImplGlfw_Shutdown();
        imguiVulkan_ = imguiGlfw_ = false;
        ImGui::DestroyContext();
    }
    destroyTargets();
    if (imguiPool_)
        vkDestroyDescriptorPool(device_.device, imguiPool_, nullptr);
    imguiPool_ = VK_NULL_HANDLE;
    for (VkRenderPass* pass : { &renderPass_, &uiPass_, &reducedPass_ }) {
        if (*pass)
            vkDestroyRenderPass(device_.device, *pass, nullptr);
        *pass = VK_NULL_HANDLE;
    }
    loop_.reset();
    if (device_.device)
        gpu::destroyDevice(device_);
    device_ = {};
    if (surface_)
        vkDestroySurfaceKHR(instance_.instance, surface_, nullptr);
    surface_ = VK_NULL_HANDLE;
    if (instance_.instance)
        gpu::destroyInstance(instance_);
    instance_ = {};
    if (window_) {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    window_ = nullptr;
}

VkFormat Window::colorFormat() const
{
    return loop_->swapchain().format;
}

double Window::contentScale() const
{
    int fw = 0, fh = 0, ww = 0, wh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    glfwGetWindowSize(window_, &ww, &wh);
    if (ww > 0 && fw > 0)
        return static_cast<double>(fw) / ww;
    float sx = 1, sy = 1;
    glfwGetWindowContentScale(window_, &sx, &sy);
    return sx;
}

void Window::cursor(double& x, double& y) const
{
    glfwGetCursorPos(window_, &x, &y);
    const double s = contentScale();
    x *= s;
    y *= s;
}

void Window::createLoop(Present present, VkExtent2D size)
{
    // A device that draws on the CPU (lavapipe) presents through Mesa's software WSI, which sends
    // each frame through the X socket; MIT-SHM hands it over in shared memory instead
    // (gui/x11_shm_sink.h). A GPU's swapchain is the fast path there.
    const bool cpuDevice = device_.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    std::string whyNot;
    if (present == Present::Shm || (present == Present::Auto && cpuDevice)) {
        if (auto sink = createX11ShmSink(window_, size, whyNot)) {
            loop_ = std::make_unique<gpu::FrameLoop>(device_, std::move(sink), size);
            presentPath_ = "MIT-SHM";
            return;
        }
        if (present == Present::Shm)
            fail("gui: cannot present by MIT-SHM: ", whyNot);
    }
    VkSurfaceCapabilitiesKHR caps {};
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device_.physical, surface_, &caps));
    gpu::SwapchainOptions so;
    if (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)
        so.extraUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    loop_ = std::make_unique<gpu::FrameLoop>(device_, surface_, size, so);
    presentPath_ = whyNot.empty() ? "swapchain" : "swapchain (MIT-SHM: " + whyNot + ")";
}

void Window::eventCursor(double& x, double& y) const
{
    if (!lastEvent_)
        return cursor(x, y);
    x = lastEvent_->x;
    y = lastEvent_->y;
}

bool Window::shouldClose() const
{
    return glfwWindowShouldClose(window_);
}

void Window::requestClose()
{
    glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

namespace {

void destroyReduced(gpu::Device& device, Window::Targets& t)
{
    if (t.reducedFramebuffer)
        vkDestroyFramebuffer(device.device, t.reducedFramebuffer, nullptr);
    t.reducedFramebuffer = VK_NULL_HANDLE;
    for (gpu::Image* i : { &t.reducedDepth, &t.reduced })
        if (i->image)
            gpu::destroyImage(device, *i);
    t.reducedExtent = {};
}

void destroy(gpu::Device& device, Window::Targets& t)
{
    destroyReduced(device, t);
    for (VkFramebuffer f : t.framebuffers)
        vkDestroyFramebuffer(device.device, f, nullptr);
    for (VkFramebuffer f : t.uiFramebuffers)
        vkDestroyFramebuffer(device.device, f, nullptr);
    if (t.color.image)
        gpu::destroyImage(device, t.color);
    if (t.depth.image)
        gpu::destroyImage(device, t.depth);
    if (t.readback.buffer)
        gpu::destroyBuffer(device, t.readback);
}

} // namespace

void Window::destroyTargets()
{
    if (targets_)
        destroy(device_, *targets_);
    targets_.reset();
}

void Window::createTargets()
{
    const gpu::Swapchain& sc = loop_->swapchain();
    auto t = std::make_unique<Targets>();
    t->extent = sc.extent;
    const VkSampleCountFlagBits samples = samples_ == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
    if (samples_ == 4)
        t->color = gpu::createImage(device_, sc.extent.width, sc.extent.height, sc.format,
            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT, VK_IMAGE_ASPECT_COLOR_BIT, samples);
    t->depth = gpu::createImage(device_, sc.extent.width, sc.extent.height, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
        VK_IMAGE_ASPECT_DEPTH_BIT, samples);
    for (VkImageView view : sc.views) {
        std::vector<VkImageView> views;
        if (samples_ == 4)
            views = { t->color.view, t->depth.view, view };
        else
            views = { view, t->depth.view };
        auto info = gpu::makeStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
        info.renderPass = renderPass_;
        info.attachmentCount = static_cast<std::uint32_t>(views.size());
        info.pAttachments = views.data();
        info.width = sc.extent.width;
        info.height = sc.extent.height;
        info.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        VK_CHECK(vkCreateFramebuffer(device_.device, &info, nullptr, &fb));
        t->framebuffers.push_back(fb);
        info.renderPass = uiPass_;
        info.attachmentCount = 1;
        info.pAttachments = &view;
        VK_CHECK(vkCreateFramebuffer(device_.device, &info, nullptr, &fb));
        t->uiFramebuffers.push_back(fb);
    }
    if (sc.usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT)
        t->readback = gpu::createBuffer(device_, VkDeviceSize(sc.extent.width) * sc.extent.height * 4, 0, gpu::MemoryUse::Readback);
    targets_ = std::move(t);
    targetsFor_ = loop_->imagesGeneration();
}

void Window::createReduced(VkExtent2D extent)
{
    Targets& t = *targets_;
    if (t.reducedFramebuffer) {
        // Another size: the old images may still be used by a frame in flight.
        auto old = std::make_shared<Targets>();
        std::swap(old->reducedDepth, t.reducedDepth);
        std::swap(old->reduced, t.reduced);
        std::swap(old->reducedFramebuffer, t.reducedFramebuffer);
        loop_->defer([this, old] { destroyReduced(device_, *old); });
    }
    t.reduced = gpu::createImage(device_, extent.width, extent.height, colorFormat(),
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    t.reducedDepth = gpu::createImage(
        device_, extent.width, extent.height, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    const VkImageView views[2] = { t.reduced.view, t.reducedDepth.view };
    auto info = gpu::makeStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
    info.renderPass = reducedPass_;
    info.attachmentCount = 2;
    info.pAttachments = views;
    info.width = extent.width;
    info.height = extent.height;
    info.layers = 1;
    VK_CHECK(vkCreateFramebuffer(device_.device, &info, nullptr, &t.reducedFramebuffer));
    t.reducedExtent = extent;
}

bool Window::begin(gpu::Frame& frame, const float background[4], double sceneScale)
{
    if (!(sceneScale > 0 && sceneScale <= 1))
        fail("gui: the scene's scale must be in (0, 1], got ", sceneScale);
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    imguiFrame_ = true;
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (!loop_->beginFrame({ std::uint32_t(w), std::uint32_t(h) }, frame))
        return false;
    if (!targets_ || targetsFor_ != loop_->imagesGeneration()) {
        // The frame loop's images were remade (a new swapchain or size): the old targets may
        // still be used by a frame in flight.
        if (targets_) {
            std::shared_ptr<Targets> old(std::move(targets_));
            loop_->defer([this, old] { destroy(device_, *old); });
        }
        createTargets();
    }
    VkClearValue clear[3] {};
    for (int i = 0; i < 4; ++i)
        clear[0].color.float32[i] = background[i];
    clear[1].depthStencil = { 1.0f, 0 };
    clear[2] = clear[0];
    sceneExtent_ = frame.extent;
    reducedFrame_ = false;
    if (sceneScale < 1 && canReduce_) {
        const VkExtent2D e { std::max(1u, std::uint32_t(std::lround(frame.extent.width * sceneScale))),
            std::max(1u, std::uint32_t(std::lround(frame.extent.height * sceneScale))) };
        if (e.width < frame.extent.width && e.height < frame.extent.height) {
            if (e.width != targets_->reducedExtent.width || e.height != targets_->reducedExtent.height)
                createReduced(e);
            sceneExtent_ = e;
            reducedFrame_ = true;
        }
    }
    auto rp = gpu::makeStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    rp.renderPass = reducedFrame_ ? reducedPass_ : renderPass_;
    rp.framebuffer = reducedFrame_ ? targets_->reducedFramebuffer : targets_->framebuffers[frame.imageIndex];
    rp.renderArea.extent = sceneExtent_;
    rp.clearValueCount = samples_ == 4 && !reducedFrame_ ? 3 : 2;
    rp.pClearValues = clear;
    vkCmdBeginRenderPass(frame.cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    return true;
}

void Window::skipFrame()
{
    if (imguiFrame_)
        ImGui::EndFrame();
    imguiFrame_ = false;
}

void Window::end(gpu::Frame& frame, bool capture)
{
    ImGui::Render();
    imguiFrame_ = false;
    vkCmdEndRenderPass(frame.cmd);
    if (reducedFrame_) {
        // The reduced scene, scaled up (bilinear) over the whole swapchain image.
        const VkImage reduced = targets_->reduced.image;
        gpu::imageBarrier(frame.cmd, reduced, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        // From colour output, where the acquire semaphore is waited for: the blit waits for it too.
        gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_TRANSFER_WRITE_BIT);
        VkImageBlit region {};
        region.srcSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 };
        region.srcOffsets[1] = { std::int32_t(sceneExtent_.width), std::int32_t(sceneExtent_.height), 1 };
        region.dstSubresource = region.srcSubresource;
        region.dstOffsets[1] = { std::int32_t(frame.extent.width), std::int32_t(frame.extent.height), 1 };
        vkCmdBlitImage(frame.cmd, reduced, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, frame.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
            &region, VK_FILTER_LINEAR);
        gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    }
    auto rp = gpu::makeStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    rp.renderPass = uiPass_;
    rp.framebuffer = targets_->uiFramebuffers[frame.imageIndex];
    rp.renderArea.extent = frame.extent;
    vkCmdBeginRenderPass(frame.cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), frame.cmd);
    vkCmdEndRenderPass(frame.cmd);
    captured_ = false;
    if (capture && targets_->readback.buffer) {
        // The copy is read by the host once the frame's fence has passed.
        gpu::copyImageToHost(frame.cmd, frame.image, frame.extent, targets_->readback.buffer);
        gpu::imageBarrier(frame.cmd, frame.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
            VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
        captured_ = true;
    }
    loop_->endFrame(frame);
}

Image Window::screenshot()
{
    if (!captured_)
        fail("gui: no frame was captured (the surface does not allow copying its images)");
    loop_->waitFrames();
    const VkExtent2D e = targets_->extent;
    Image image;
    image.width = static_cast<int>(e.width);
    image.height = static_cast<int>(e.height);
    image.pixels.resize(static_cast<size_t>(e.width) * e.height * 4);
    gpu::readbackBuffer(device_, targets_->readback, image.pixels.data(), image.pixels.size());
    const VkFormat f = colorFormat();
    if (f == VK_FORMAT_B8G8R8A8_UNORM || f == VK_FORMAT_B8G8R8A8_SRGB)
        for (size_t i = 0; i < image.pixels.size(); i += 4)
            std::swap(image.pixels[i], image.pixels[i + 2]);
    for (size_t i = 3; i < image.pixels.size(); i += 4)
        image.pixels[i] = 255; // the window is opaque
    return image;
}

void Window::waitIdle()
{
    loop_->waitFrames();
}

} // namespace facesketch::gui

#include "gpu/swapchain.h"

#include "core/error.h"

#include <algorithm>

namespace facesketch::gpu {

namespace {

VkSurfaceFormatKHR chooseFormat(Device& device, VkSurfaceKHR surface, bool srgb)
{
    std::uint32_t count = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(device.physical, surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(device.physical, surface, &count, formats.data()));
    const VkFormat preferred[]
        = { srgb ? VK_FORMAT_B8G8R8A8_SRGB : VK_FORMAT_B8G8R8A8_UNORM, srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM,
              srgb ? VK_FORMAT_B8G8R8A8_UNORM : VK_FORMAT_B8G8R8A8_SRGB, srgb ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_R8G8B8A8_SRGB };
    for (VkFormat want : preferred)
        for (const VkSurfaceFormatKHR& f : formats)
            if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
                return f;
    fail("the window surface offers no 8-bit BGRA or RGBA format (", count, " formats seen)");
}

VkSemaphore createSemaphore(Device& device)
{
    auto info = makeStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    VkSemaphore semaphore;
    VK_CHECK(vkCreateSemaphore(device.device, &info, nullptr, &semaphore));
    return semaphore;
}

// Images, views and semaphores of a new VkSwapchainKHR; `old` (may be null) is retired by it.
void build(Device& device, Swapchain& s, VkExtent2D size, VkSwapchainKHR old)
{
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device.physical, s.surface, &caps));
    // A current extent of 0xFFFFFFFF means the window takes the swapchain's size.
    VkExtent2D extent = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent : size;
    if (size.width == 0 || size.height == 0 || extent.width == 0 || extent.height == 0) {
        s.swapchain = VK_NULL_HANDLE;
        s.extent = { 0, 0 };
        return;
    }
    extent.width = std::clamp(extent.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(extent.height, caps.minImageExtent.height, caps.maxImageExtent.height);

    const VkSurfaceFormatKHR format = chooseFormat(device, s.surface, s.options.srgb);
    s.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) | s.options.extraUsage;
    if ((caps.supportedUsageFlags & s.usage) != s.usage)
        fail("the window surface does not support the image usage ", s.usage, " (supported: ", caps.supportedUsageFlags, ")");

    // One image more than the minimum, so that acquiring never waits for the presentation engine
    // to let go of the image it scans out.
    std::uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0)
        imageCount = std::min(imageCount, caps.maxImageCount);

    auto info = makeStruct<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
    info.surface = s.surface;
    info.minImageCount = imageCount;
    info.imageFormat = format.format;
    info.imageColorSpace = format.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = s.usage;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR) ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                                                                                           : caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
        ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
        : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR; // the one mode every driver has; paces the loop to the display
    info.clipped = VK_TRUE;
    info.oldSwapchain = old;
    if (VkResult r = vkCreateSwapchainKHR(device.device, &info, nullptr, &s.swapchain); r != VK_SUCCESS)
        gpuFail(cat("creating a ", extent.width, "x", extent.height, " swapchain (vkCreateSwapchainKHR)"), r);
    s.format = format.format;
    s.colorSpace = format.colorSpace;
    s.extent = extent;

    std::uint32_t count = 0;
    VK_CHECK(vkGetSwapchainImagesKHR(device.device, s.swapchain, &count, nullptr));
    s.images.resize(count);
    VK_CHECK(vkGetSwapchainImagesKHR(device.device, s.swapchain, &count, s.images.data()));
    for (VkImage image : s.images) {
        auto view = makeStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        view.image = image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = s.format;
        view.subresourceRange = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1 };
        VkImageView v;
        VK_CHECK(vkCreateImageView(device.device, &view, nullptr, &v));
        s.views.push_back(v);
        s.renderFinished.push_back(createSemaphore(device));
    }
}

// Views and semaphores only: the VkSwapchainKHR is destroyed by the caller.
void releaseImages(Device& device, Swapchain& s)
{
    for (VkImageView v : s.views)
        vkDestroyImageView(device.device, v, nullptr);
    for (VkSemaphore semaphore : s.renderFinished)
        vkDestroySemaphore(device.device, semaphore, nullptr);
    s.views.clear();
    s.renderFinished.clear();
    s.images.clear();
}

} // namespace

Swapchain createSwapchain(Device& device, VkSurfaceKHR surface, VkExtent2D framebufferSize, const SwapchainOptions& options)
{
    if (!device.swapchain)
        fail("createSwapchain: the device was created without VK_KHR_swapchain (LogicalDeviceOptions::swapchain)");
    if (!surface)
        fail("createSwapchain: no surface");
    Swapchain s;
    s.surface = surface;
    s.options = options;
    build(device, s, framebufferSize, VK_NULL_HANDLE);
    return s;
}

bool recreateSwapchain(Device& device, Swapchain& s, VkExtent2D framebufferSize)
{
    const VkSwapchainKHR old = s.swapchain;
    releaseImages(device, s);
    try {
        build(device, s, framebufferSize, old);
    } catch (...) {
        if (old)
            vkDestroySwapchainKHR(device.device, old, nullptr);
        s.swapchain = VK_NULL_HANDLE;
        throw;
    }
    if (old)
        vkDestroySwapchainKHR(device.device, old, nullptr);
    return s.swapchain != VK_NULL_HANDLE;
}

void destroySwapchain(Device& device, Swapchain& s)
{
    releaseImages(device, s);
    if (s.swapchain)
        vkDestroySwapchainKHR(device.device, s.swapchain, nullptr);
    s = Swapchain {};
}

FrameLoop::FrameLoop(Device& device, VkSurfaceKHR surface, VkExtent2D framebufferSize, const SwapchainOptions& options)
    : device_(device)
{
    swapchain_ = createSwapchain(device, surface, framebufferSize, options);
    generation_ = 1;
    createSlots();
}

FrameLoop::FrameLoop(Device& device, std::unique_ptr<FrameSink> sink, VkExtent2D framebufferSize, const SwapchainOptions& options)
    : device_(device)
    , sink_(std::move(sink))
{
    if (!sink_)
        fail("FrameLoop: no frame sink");
    const VkFormat format = sink_->format();
    if (format != VK_FORMAT_B8G8R8A8_UNORM && format != VK_FORMAT_R8G8B8A8_UNORM)
        fail("FrameLoop: a frame sink must take B8G8R8A8_UNORM or R8G8B8A8_UNORM, not format ", int(format));
    swapchain_.format = format;
    swapchain_.options = options;
    swapchain_.usage
        = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | options.extraUsage;
    try {
        if (framebufferSize.width > 0 && framebufferSize.height > 0)
            createSinkImages(framebufferSize);
    } catch (...) {
        destroySinkImages();
        throw;
    }
    createSlots();
}

void FrameLoop::createSinkImages(VkExtent2D size)
{
    for (std::uint32_t i = 0; i < framesInFlight; ++i) {
        sinkImages_.push_back(
            createImage(device_, size.width, size.height, swapchain_.format, swapchain_.usage, VK_IMAGE_ASPECT_COLOR_BIT));
        sinkPixels_.push_back(createBuffer(device_, VkDeviceSize(size.width) * size.height * 4, 0, MemoryUse::Readback));
        if (!sinkPixels_.back().mapped)
            fail("FrameLoop: the device has no host-visible memory for a frame sink");
        swapchain_.images.push_back(sinkImages_.back().image);
        swapchain_.views.push_back(sinkImages_.back().view);
    }
    swapchain_.extent = size;
    ++generation_;
}

void FrameLoop::destroySinkImages()
{
    for (Image& image : sinkImages_)
        destroyImage(device_, image);
    for (Buffer& buffer : sinkPixels_)
        destroyBuffer(device_, buffer);
    sinkImages_.clear();
    sinkPixels_.clear();
    swapchain_.images.clear();
    swapchain_.views.clear();
    swapchain_.extent = {};
}

void FrameLoop::createSlots()
{
    try {
        for (Slot& slot : slots_) {
            auto pool = makeStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
            pool.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
            pool.queueFamilyIndex = device_.queueFamily;
            VK_CHECK(vkCreateCommandPool(device_.device, &pool, nullptr, &slot.pool));
            auto alloc = makeStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
            alloc.commandPool = slot.pool;
            alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
            alloc.commandBufferCount = 1;
            VK_CHECK(vkAllocateCommandBuffers(device_.device, &alloc, &slot.cmd));
            // Created signalled: the first wait on each slot returns at once.
            auto fence = makeStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
            fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
            VK_CHECK(vkCreateFence(device_.device, &fence, nullptr, &slot.fence));
            slot.imageAcquired = createSemaphore(device_);
        }
    } catch (...) {
        release();
        throw;
    }
}

FrameLoop::~FrameLoop()
{
    release();
}

void FrameLoop::release()
{
    for (Slot& slot : slots_)
        if (slot.fence)
            vkWaitForFences(device_.device, 1, &slot.fence, VK_TRUE, UINT64_MAX);
    // The last presents wait on semaphores destroyed below and have no fence.
    vkQueueWaitIdle(device_.queue);
    runReleases(true);
    for (Slot& slot : slots_) {
        if (slot.imageAcquired)
            vkDestroySemaphore(device_.device, slot.imageAcquired, nullptr);
        if (slot.fence)
            vkDestroyFence(device_.device, slot.fence, nullptr);
        if (slot.pool)
            vkDestroyCommandPool(device_.device, slot.pool, nullptr);
        slot = Slot {};
    }
    if (sink_)
        destroySinkImages();
    else
        destroySwapchain(device_, swapchain_);
}

void FrameLoop::runReleases(bool all)
{
    // Move the ready ones out first: a release may defer another.
    std::vector<std::function<void()>> ready;
    for (auto it = releases_.begin(); it != releases_.end();) {
        if (!all && it->waitsLeft > 0)
            ++it;
        else {
            ready.push_back(std::move(it->release));
            it = releases_.erase(it);
        }
    }
    for (auto& release : ready)
        release();
}

void FrameLoop::waitFrames()
{
    VkFence fences[framesInFlight];
    for (std::uint32_t i = 0; i < framesInFlight; ++i)
        fences[i] = slots_[i].fence;
    if (VkResult r = vkWaitForFences(device_.device, framesInFlight, fences, VK_TRUE, UINT64_MAX); r != VK_SUCCESS)
        gpuFail("waiting for the frames in flight (vkWaitForFences)", r);
    runReleases(true);
}

void FrameLoop::defer(std::function<void()> release)
{
    releases_.push_back({ framesInFlight, std::move(release) });
}

bool FrameLoop::beginFrame(VkExtent2D size, Frame& frame)
{
    if (recording_)
        fail("FrameLoop::beginFrame: the previous frame was not ended");
    if (size.width == 0 || size.height == 0) {
        waitFrames();
        return false;
    }
    if (sink_ && (size.width != swapchain_.extent.width || size.height != swapchain_.extent.height)) {
        waitFrames(); // frames in flight still draw into the old images
        destroySinkImages();
        createSinkImages(size);
    } else if (!sink_
        && (outOfDate_ || !swapchain_.swapchain || size.width != swapchain_.extent.width || size.height != swapchain_.extent.height)) {
        // The old images may still be drawn into by frames in flight: wait for their fences,
        // then for the queue, whose presents (which have no fence without
        // VK_EXT_swapchain_maintenance1) still wait on the old render-finished semaphores.
        waitFrames();
        if (VkResult r = vkQueueWaitIdle(device_.queue); r != VK_SUCCESS)
            gpuFail("waiting for the presents before rebuilding the swapchain (vkQueueWaitIdle)", r);
        outOfDate_ = false;
        if (!recreateSwapchain(device_, swapchain_, size))
            return false;
        ++generation_;
    }

    const std::uint32_t index = static_cast<std::uint32_t>(frameNumber_ % framesInFlight);
    Slot& slot = slots_[index];
    if (VkResult r = vkWaitForFences(device_.device, 1, &slot.fence, VK_TRUE, UINT64_MAX); r != VK_SUCCESS)
        gpuFail("waiting for a frame in flight (vkWaitForFences)", r);
    for (Release& release : releases_)
        release.waitsLeft -= release.waitsLeft > 0;
    runReleases(false);

    // A sink's images are the slots' own: the slot's fence has just said its image is free.
    std::uint32_t imageIndex = index;
    if (!sink_) {
        const VkResult acquired
            = vkAcquireNextImageKHR(device_.device, swapchain_.swapchain, UINT64_MAX, slot.imageAcquired, VK_NULL_HANDLE, &imageIndex);
        if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
            outOfDate_ = true; // the semaphore was not signalled: nothing to undo
            return false;
        }
        if (acquired == VK_SUBOPTIMAL_KHR)
            outOfDate_ = true; // the image is acquired and the semaphore signalled: draw it, rebuild next time
        else if (acquired != VK_SUCCESS)
            gpuFail("acquiring a swapchain image (vkAcquireNextImageKHR)", acquired);
    }

    // Reset only now that a submission will follow: a skipped frame leaves the fence signalled.
    VK_CHECK(vkResetFences(device_.device, 1, &slot.fence));
    VK_CHECK(vkResetCommandPool(device_.device, slot.pool, 0));
    auto begin = makeStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));

    ++frameNumber_;
    frame.cmd = slot.cmd;
    frame.slot = index;
    frame.number = frameNumber_;
    frame.imageIndex = imageIndex;
    frame.image = swapchain_.images[imageIndex];
    frame.view = swapchain_.views[imageIndex];
    frame.format = swapchain_.format;
    frame.extent = swapchain_.extent;
    recording_ = true;
    return true;
}

void FrameLoop::endFrame(Frame& frame)
{
    if (!recording_)
        fail("FrameLoop::endFrame: no frame was begun");
    recording_ = false;
    Slot& slot = slots_[frame.slot];
    if (sink_) {
        endSinkFrame(frame);
        return;
    }
    VK_CHECK(vkEndCommandBuffer(frame.cmd));

    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSemaphore finished = swapchain_.renderFinished[frame.imageIndex];
    auto submit = makeStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &slot.imageAcquired;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &frame.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &finished;
    if (VkResult r = vkQueueSubmit(device_.queue, 1, &submit, slot.fence); r != VK_SUCCESS)
        gpuFail("submitting a frame (vkQueueSubmit)", r);

    auto present = makeStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &finished;
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain_.swapchain;
    present.pImageIndices = &frame.imageIndex;
    const VkResult presented = vkQueuePresentKHR(device_.queue, &present);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR)
        outOfDate_ = true;
    else if (presented != VK_SUCCESS)
        gpuFail("presenting a frame (vkQueuePresentKHR)", presented);
}

void FrameLoop::endSinkFrame(Frame& frame)
{
    Slot& slot = slots_[frame.slot];
    const Buffer& pixels = sinkPixels_[frame.imageIndex];
    // The finished image to host memory (a screenshot's copy leaves it in PRESENT_SRC_KHR too).
    copyImageToHost(frame.cmd, frame.image, frame.extent, pixels.buffer);
    VK_CHECK(vkEndCommandBuffer(frame.cmd));

    auto submit = makeStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &frame.cmd;
    if (VkResult r = vkQueueSubmit(device_.queue, 1, &submit, slot.fence); r != VK_SUCCESS)
        gpuFail("submitting a frame (vkQueueSubmit)", r);
    // Shown as soon as it is drawn, as a FIFO present would: the frame's time includes its showing.
    if (VkResult r = vkWaitForFences(device_.device, 1, &slot.fence, VK_TRUE, UINT64_MAX); r != VK_SUCCESS)
        gpuFail("waiting for a frame to show (vkWaitForFences)", r);
    sink_->show(static_cast<const std::uint8_t*>(pixels.mapped), frame.extent);
}

void copyImageToHost(VkCommandBuffer cmd, VkImage image, VkExtent2D extent, VkBuffer buffer)
{
    imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferImageCopy region {};
    region.imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 };
    region.imageExtent = { extent.width, extent.height, 1 };
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
    auto toHost = makeStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0, nullptr);
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout oldLayout, VkImageLayout newLayout,
    VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage, VkAccessFlags dstAccess)
{
    auto barrier = makeStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    barrier.srcAccessMask = srcAccess;
    barrier.dstAccessMask = dstAccess;
    barrier.oldLayout = oldLayout;
    barrier.newLayout = newLayout;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = { aspect, 0, 1, 0, 1 };
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

} // namespace facesketch::gpu

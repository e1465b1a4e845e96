#pragma once
// Presenting to a window: the swapchain of a surface the app made (glfwCreateWindowSurface on an
// instance from createInstance with the window's extensions, a device from createDevice with
// `.swapchain = true`), and the frame loop around it: two frames in flight, each with its own
// command buffer, fence and acquire semaphore, so the CPU records frame N+1 while the GPU draws
// frame N, and per-frame resources are released by fences, never by idling the device.
//
//   gpu::FrameLoop loop(device, surface, { width, height });
//   while (!glfwWindowShouldClose(window)) {
//       glfwPollEvents();
//       int w, h;
//       glfwGetFramebufferSize(window, &w, &h);           // pixels (HiDPI), 0 x 0 when minimised
//       gpu::Frame frame;
//       if (!loop.beginFrame({ std::uint32_t(w), std::uint32_t(h) }, frame))
//           continue;                                      // minimised or out of date: no frame
//       // frame.image is in VK_IMAGE_LAYOUT_UNDEFINED (its old contents are not kept): record
//       // a transition, the passes, and a transition to VK_IMAGE_LAYOUT_PRESENT_SRC_KHR
//       loop.endFrame(frame);                              // submits and presents
//   }
//   // destroy the loop before the device and the surface
//
// Lifetime rule: anything a recorded frame uses (buffers, images, descriptor data) stays alive
// until that frame's fence has passed. Per-slot resources (indexed by Frame::slot) may be
// rewritten in beginFrame's wake; anything else is released through FrameLoop::defer.

#include "gpu/buffers.h"
#include "gpu/device.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace facesketch::gpu {

/// Frames the CPU may record ahead of the GPU. Two: the GPU draws one while the CPU records the next.
constexpr std::uint32_t framesInFlight = 2;

struct SwapchainOptions {
    /// Prefer a *_SRGB format, where the hardware encodes the shader's linear colours. The
    /// default, UNORM, shows colours as written, exactly as the PNGs of the offscreen renderer.
    bool srgb = false;
    /// Image usage beyond COLOR_ATTACHMENT; TRANSFER_SRC (for screenshots) is added when the
    /// surface supports it.
    VkImageUsageFlags extraUsage = 0;
};

struct Swapchain {
    VkSwapchainKHR swapchain = VK_NULL_HANDLE; ///< null while the window is minimised (zero size)
    VkSurfaceKHR surface = VK_NULL_HANDLE;     ///< not owned
    VkFormat format = VK_FORMAT_UNDEFINED;     ///< B8G8R8A8_UNORM or _SRGB when the surface offers them
    VkColorSpaceKHR colorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    VkExtent2D extent {}; ///< pixels
    VkImageUsageFlags usage = 0;
    std::vector<VkImage> images;             ///< owned by the swapchain
    std::vector<VkImageView> views;          ///< one per image
    std::vector<VkSemaphore> renderFinished; ///< one per image: the present waits on it
    SwapchainOptions options;
};

/// A FIFO (vsync) swapchain for `surface` at `framebufferSize` pixels (the surface's current
/// extent wins when it has one; the size is clamped to the surface's limits). Returns a Swapchain
/// whose `swapchain` is null when the size is zero (minimised). Throws Error when the surface
/// offers no 8-bit BGRA/RGBA format; GpuError on a failed Vulkan call.
Swapchain createSwapchain(Device& device, VkSurfaceKHR surface, VkExtent2D framebufferSize, const SwapchainOptions& options = {});
/// Rebuilds `swapchain` for a new size (passing the old one as oldSwapchain, then destroying it).
/// Every frame that used the old images must have finished (FrameLoop does this by its fences).
/// Returns false, leaving no swapchain, when the size is zero.
bool recreateSwapchain(Device& device, Swapchain& swapchain, VkExtent2D framebufferSize);
void destroySwapchain(Device& device, Swapchain& swapchain);

/// One frame being recorded.
struct Frame {
    VkCommandBuffer cmd = VK_NULL_HANDLE; ///< begun (one-time submit); endFrame ends and submits it
    std::uint32_t slot = 0;               ///< 0 .. framesInFlight-1: index per-frame resources by it
    std::uint64_t number = 0;             ///< frames begun so far, this one included
    std::uint32_t imageIndex = 0;
    VkImage image = VK_NULL_HANDLE; ///< the swapchain image, in VK_IMAGE_LAYOUT_UNDEFINED
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent {}; ///< pixels; the size to draw at this frame
};

/// Where a FrameLoop without a swapchain sends each finished frame: a window-system path of the
/// app's own (gui/x11_shm_sink.h: Mesa's software WSI copies frames to the X server through its
/// socket, which costs Xvfb more than the whole frame costs lavapipe), or a test's CPU reference.
class FrameSink {
public:
    virtual ~FrameSink() = default;
    /// The format the frames are drawn in and handed over: B8G8R8A8_UNORM or R8G8B8A8_UNORM.
    virtual VkFormat format() const = 0;
    /// Shows one finished frame: extent.width * extent.height pixels of 4 bytes, rows top first
    /// and tightly packed. The pixels may be overwritten as soon as it returns.
    virtual void show(const std::uint8_t* pixels, VkExtent2D extent) = 0;
};

/// The swapchain plus a ring of framesInFlight frames (command buffer, fence, acquire semaphore).
class FrameLoop {
public:
    /// `device` must have been created with `.swapchain = true` and a queue that presents to `surface`.
    FrameLoop(Device& device, VkSurfaceKHR surface, VkExtent2D framebufferSize, const SwapchainOptions& options = {});
    /// Without a swapchain: the loop draws into images of its own (one per slot, in the sink's
    /// format, with TRANSFER_SRC and TRANSFER_DST usage) and endFrame copies each finished frame
    /// to host memory and hands it to `sink` once the GPU is done with it. The same Frame contract
    /// (images in UNDEFINED at beginFrame, PRESENT_SRC_KHR at the end of the commands), so a
    /// renderer cannot tell the two apart; `swapchain()` then has a null handle and the loop's images.
    /// The device needs `.swapchain = true` all the same: that extension makes PRESENT_SRC_KHR a layout.
    FrameLoop(Device& device, std::unique_ptr<FrameSink> sink, VkExtent2D framebufferSize, const SwapchainOptions& options = {});
    /// Waits for this loop's frames (their fences) and the queue (the last presents), runs pending
    /// releases, destroys everything.
    ~FrameLoop();
    FrameLoop(const FrameLoop&) = delete;
    FrameLoop& operator=(const FrameLoop&) = delete;

    /// Waits for the fence of the frame that last used this slot (framesInFlight frames ago), runs
    /// the releases deferred by it, recreates the swapchain when `framebufferSize` differs from its
    /// extent or the last present reported OUT_OF_DATE / SUBOPTIMAL (then, and only then, it also
    /// waits for the queue: presents have no fence), acquires an image and begins
    /// the slot's command buffer. Returns false, with nothing begun, when the size is zero
    /// (minimised) or the image could not be acquired (out of date: the next call recreates);
    /// the caller then skips drawing this frame.
    bool beginFrame(VkExtent2D framebufferSize, Frame& frame);
    /// Ends the command buffer, submits it (waiting for the acquired image at colour-attachment
    /// output, signalling the image's render-finished semaphore and the slot's fence) and
    /// presents. The image must be in VK_IMAGE_LAYOUT_PRESENT_SRC_KHR at the end of the commands.
    /// OUT_OF_DATE and SUBOPTIMAL mark the swapchain for recreation at the next beginFrame.
    void endFrame(Frame& frame);

    /// Runs `release` once the GPU has finished every frame submitted so far and the one being
    /// recorded (for buffers or images replaced while frames may still read them).
    void defer(std::function<void()> release);
    /// Waits for the fences of all frames in flight and runs every pending release (not in the
    /// frame loop: at teardown, or before destroying something shared by all frames).
    void waitFrames();

    const Swapchain& swapchain() const { return swapchain_; }
    /// Counts the times the images were (re)created: per-image resources made for another
    /// generation are stale.
    std::uint64_t imagesGeneration() const { return generation_; }
    /// Whether frames go to a FrameSink rather than a swapchain.
    bool presentsToSink() const { return sink_ != nullptr; }
    std::uint64_t framesBegun() const { return frameNumber_; }

private:
    struct Slot {
        VkCommandPool pool = VK_NULL_HANDLE;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE; ///< signalled when the slot's last submission finished
        VkSemaphore imageAcquired = VK_NULL_HANDLE;
    };
    struct Release {
        std::uint32_t waitsLeft; ///< slot fences still to wait for before `release` may run
        std::function<void()> release;
    };
    void runReleases(bool all);
    void release();
    void createSlots();
    void endSinkFrame(Frame& frame);
    /// Sink mode: the loop's own images and their host copies at `size`.
    void createSinkImages(VkExtent2D size);
    void destroySinkImages();
    Device& device_;
    Swapchain swapchain_;
    std::unique_ptr<FrameSink> sink_;
    std::vector<Image> sinkImages_;  ///< one per slot
    std::vector<Buffer> sinkPixels_; ///< one per slot, host-visible
    std::uint64_t generation_ = 0;
    Slot slots_[framesInFlight];
    std::vector<Release> releases_;
    std::uint64_t frameNumber_ = 0;
    bool recording_ = false;
    bool outOfDate_ = false;
};

/// Records the copy of a whole colour `image` of `extent` pixels, in VK_IMAGE_LAYOUT_PRESENT_SRC_KHR
/// after colour output or a transfer wrote it, into `buffer` (rows tightly packed), and the
/// barrier that makes the copy visible to the host once the commands' fence has passed. The
/// image is left in VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL. (FrameLoop's sink mode, screenshots.)
void copyImageToHost(VkCommandBuffer cmd, VkImage image, VkExtent2D extent, VkBuffer buffer);

/// Records an image layout transition with a full pipeline barrier between the given stages and
/// accesses, for one mip level and layer of `aspect`.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout oldLayout, VkImageLayout newLayout,
    VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

} // namespace facesketch::gpu

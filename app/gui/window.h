#pragma once
// The app's window: GLFW (no client API), a Vulkan device that presents to it (gpu/device.h's
// three steps), the frame loop (gpu/swapchain.h: through the Vulkan swapchain, or for a device
// that draws on the CPU under X11 through MIT-SHM, gui/x11_shm_sink.h; see Present), one render
// pass that the scene (render/scene_renderer.h) and ImGui (Debian's imgui_impl_glfw /
// imgui_impl_vulkan, built into the app) draw into, and screenshots of the presented image. HiDPI: everything is in
// framebuffer pixels; contentScale() scales the ImGui style and fonts and converts GLFW's
// cursor positions (screen coordinates) to pixels.
//
// Two render passes per frame. The scene's (renderPass()): 4x MSAA colour and depth resolved into
// the swapchain image (samples() = 4), or with samples 1 drawing into that image itself. Then
// ImGui's, one sample per pixel, blending over the image the scene left (loaded) and presenting it.
// While the view moves the app may draw the scene at a reduced resolution (begin()'s sceneScale):
// the scene then renders in reducedRenderPass() (one sample per pixel, no MSAA) into a smaller
// image of its own, which end() scales up over the swapchain image with a bilinear blit before
// ImGui's pass, so the panels stay sharp. The MSAA, depth and reduced images are shared by the frames in flight; each
// pass's external dependency orders one frame's use after the last.

#include "gpu/device.h"
#include "gpu/swapchain.h"
#include "io/png.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>

struct GLFWwindow;

namespace facesketch::gui {

/// How finished frames reach the window.
enum class Present {
    /// MIT-SHM (gui/x11_shm_sink.h) when the device draws on the CPU and the X server attaches the
    /// segment, else the swapchain.
    Auto,
    Swapchain, ///< the Vulkan swapchain (VK_KHR_swapchain), as on any GPU
    Shm,       ///< MIT-SHM or an error saying why not
};

struct WindowOptions {
    int width = 1280; ///< framebuffer pixels asked for (the window is sized so on HiDPI too)
    int height = 800;
    std::string title = "FaceSketch";
    int samples = 4; ///< 1 or 4
    Present present = Present::Auto;
};

/// Input for the app, called from glfwPollEvents before ImGui sees the event. Positions in
/// framebuffer pixels (x right, y down); buttons, actions, keys and mods are GLFW's values.
struct WindowEvents {
    std::function<void(int button, int action, int mods, double x, double y)> mouseButton;
    std::function<void(double x, double y)> cursor;
    std::function<void(double steps)> scroll;
    std::function<void(int key, int action, int mods)> key;
};

class Window {
public:
    struct Targets; ///< the render pass's images and framebuffers for one swapchain
    /// Opens the window and creates the device, swapchain, render pass and ImGui. Throws Error
    /// when GLFW cannot open a window (no display) or Vulkan cannot present to it.
    explicit Window(const WindowOptions& options);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* glfw() const { return window_; }
    gpu::Device& device() { return device_; }
    VkRenderPass renderPass() const { return renderPass_; }
    /// The scene's pass in reduced frames (reducedFrame()): colour and depth, one sample.
    VkRenderPass reducedRenderPass() const { return reducedPass_; }
    VkFormat colorFormat() const;
    int samples() const { return samples_; }
    /// Whether begin() can draw the scene at a reduced resolution (the surface allows blits into
    /// its images and the format linear filtering); when not, every frame is full size.
    bool canReduce() const { return canReduce_; }
    /// Framebuffer pixels per screen coordinate (1 on a normal display, 2 on a 2x HiDPI one).
    double contentScale() const;
    bool shouldClose() const;
    void setEvents(WindowEvents events) { events_ = std::move(events); }
    /// The cursor in framebuffer pixels, where it is now (a round trip to the X server).
    void cursor(double& x, double& y) const;
    void requestClose();

    /// Starts a frame: acquires an image (false when minimised or out of date: skip the
    /// frame), starts ImGui's frame and begins the scene's pass cleared to `background`, at
    /// `sceneScale` (in (0, 1]) times the window's size in each direction (rounded; full size
    /// when 1, when canReduce() is false, or when the scaled size is not smaller). Between begin
    /// and end the caller records its scene into frame.cmd with sceneExtent() as its viewport
    /// and builds its ImGui windows (drawn at full size by end()).
    bool begin(gpu::Frame& frame, const float background[4], double sceneScale = 1.0);
    /// The scene pass's size in pixels for the frame begun (frame.extent unless reduced).
    VkExtent2D sceneExtent() const { return sceneExtent_; }
    /// Whether the frame begun draws its scene at a reduced resolution.
    bool reducedFrame() const { return reducedFrame_; }
    /// Ends the scene's pass (scaling a reduced scene up into the swapchain image), draws ImGui
    /// in its pass, optionally copies the image for screenshot(), submits and presents.
    void end(gpu::Frame& frame, bool capture);
    /// Ends ImGui's frame without drawing it (when begin() returned false).
    void skipFrame();
    /// The image of the last frame ended with capture = true (waits for it), as RGBA.
    Image screenshot();
    /// Waits for every frame in flight (before replacing what they draw, at exit).
    void waitIdle();
    gpu::FrameLoop& loop() { return *loop_; }
    /// How frames reach the window, for the log: "swapchain", "MIT-SHM" or "swapchain (MIT-SHM: <why not>)".
    const std::string& presentPath() const { return presentPath_; }

private:
    void release();
    void createTargets();
    void createReduced(VkExtent2D extent);
    void destroyTargets();
    /// The cursor at the last motion event handled, so a button event queued behind it gets its
    /// own position rather than the pointer's latest one.
    void eventCursor(double& x, double& y) const;
    /// Chooses how frames reach the window (WindowOptions::present) and makes the frame loop.
    void createLoop(Present present, VkExtent2D size);

    GLFWwindow* window_ = nullptr;
    WindowEvents events_;
    struct CursorEvent {
        double x, y;
    };
    std::optional<CursorEvent> lastEvent_;
    gpu::Instance instance_;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    gpu::Device device_;
    std::unique_ptr<gpu::FrameLoop> loop_;
    int samples_ = 4;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    VkRenderPass uiPass_ = VK_NULL_HANDLE;
    VkRenderPass reducedPass_ = VK_NULL_HANDLE;
    bool canReduce_ = false;
    bool reducedFrame_ = false;
    VkExtent2D sceneExtent_ {};
    VkDescriptorPool imguiPool_ = VK_NULL_HANDLE;
    std::unique_ptr<Targets> targets_;
    std::uint64_t targetsFor_ = 0; ///< the loop's imagesGeneration() the targets were made for
    std::string presentPath_;
    bool imguiFrame_ = false;
    bool imguiGlfw_ = false, imguiVulkan_ = false;
    bool captured_ = false;
};

} // namespace facesketch::gui

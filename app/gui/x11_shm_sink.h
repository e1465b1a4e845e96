#pragma once
// Showing frames in an X11 window through shared memory (the MIT-SHM extension), for a device
// that draws on the CPU (lavapipe). Mesa 22.3's software WSI, which presents lavapipe's swapchain,
// sends every frame to the X server as PutImage requests through the socket: at 1280 x 800 that
// costs Xvfb about 22 ms of CPU per frame, more than the app's own frame (BENCHMARKS.md, "The app").
// Here the frame is copied once into a segment the server maps too, and XShmPutImage makes the
// server copy it into the window: no socket traffic for the pixels.
//
// Used by gui::Window through gpu::FrameLoop's sink mode when the device is a CPU device, the
// window is an X11 window and the server attaches the segment (a remote display cannot); else the
// window presents through the Vulkan swapchain as before (`facesketch gui --present`).

#include "gpu/swapchain.h"

#include <memory>
#include <string>

struct GLFWwindow;

namespace facesketch::gui {

/// A sink that shows frames in `window` (a GLFW window on X11) by MIT-SHM, its segment made and
/// attached for `size` pixels now (and remade when a frame has another size). Returns null, with
/// the reason in `why`, when GLFW is not on X11, the server has no MIT-SHM or cannot attach a
/// segment of this process (a remote display), or the window's visual is not 8-bit-per-channel
/// TrueColor with 32-bit pixels.
std::unique_ptr<gpu::FrameSink> createX11ShmSink(GLFWwindow* window, VkExtent2D size, std::string& why);

} // namespace facesketch::gui

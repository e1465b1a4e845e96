#include "gui/x11_shm_sink.h"

#include "core/error.h"

#include <cstring>
#include <sys/ipc.h>
#include <sys/shm.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3native.h>
// Xlib last: it defines macros (None, Bool, Status, Success) that other headers use as names.
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XShm.h>

namespace facesketch::gui {

namespace {

// Xlib reports a failed request to an error handler, whose default ends the process. Attaching a
// segment fails with BadAccess on a display that cannot map it (a remote one), which must only
// mean "present through the swapchain instead": the first error of a trapped span is kept.
int trappedError = 0;

int trapError(Display*, XErrorEvent* event)
{
    if (!trappedError)
        trappedError = event->error_code;
    return 0;
}

class X11ShmSink final : public gpu::FrameSink {
public:
    X11ShmSink(Display* display, ::Window window, Visual* visual, int depth, VkFormat format)
        : display_(display)
        , window_(window)
        , visual_(visual)
        , depth_(depth)
        , format_(format)
    {
        segment_.shmid = -1;
        gc_ = XCreateGC(display_, window_, 0, nullptr);
    }

    ~X11ShmSink() override
    {
        detach();
        XFreeGC(display_, gc_);
    }

    X11ShmSink(const X11ShmSink&) = delete;
    X11ShmSink& operator=(const X11ShmSink&) = delete;

    VkFormat format() const override { return format_; }

    /// Makes and attaches a segment for `size`; false (nothing attached) when the server refuses it.
    bool attach(VkExtent2D size, std::string& why)
    {
        detach();
        image_ = XShmCreateImage(display_, visual_, static_cast<unsigned>(depth_), ZPixmap, nullptr, &segment_, size.width, size.height);
        if (!image_) {
            why = "XShmCreateImage failed";
            return false;
        }
        if (image_->bits_per_pixel != 32) {
            why = "the window's pixels are not 32 bits";
            detach();
            return false;
        }
        segment_.shmid = shmget(IPC_PRIVATE, static_cast<size_t>(image_->bytes_per_line) * size.height, IPC_CREAT | 0600);
        if (segment_.shmid < 0) {
            why = std::string("shmget: ") + std::strerror(errno);
            detach();
            return false;
        }
        void* memory = shmat(segment_.shmid, nullptr, 0);
        if (memory == reinterpret_cast<void*>(-1)) {
            why = std::string("shmat: ") + std::strerror(errno);
            shmctl(segment_.shmid, IPC_RMID, nullptr);
            segment_.shmid = -1;
            detach();
            return false;
        }
        segment_.shmaddr = image_->data = static_cast<char*>(memory);
        segment_.readOnly = False;
        XSync(display_, False);
        trappedError = 0;
        XErrorHandler previous = XSetErrorHandler(trapError);
        const bool sent = XShmAttach(display_, &segment_);
        XSync(display_, False);
        XSetErrorHandler(previous);
        // Marked for removal now that both sides have it mapped: it goes when both detach, also
        // when this process is killed.
        shmctl(segment_.shmid, IPC_RMID, nullptr);
        attached_ = sent && !trappedError;
        if (!attached_) {
            why = "the X server cannot attach this process's shared memory (X error " + std::to_string(trappedError) + ")";
            detach();
            return false;
        }
        size_ = size;
        return true;
    }

    void show(const std::uint8_t* pixels, VkExtent2D extent) override
    {
        if (!image_ || extent.width != size_.width || extent.height != size_.height) {
            std::string why;
            if (!attach(extent, why))
                fail("gui: showing a ", extent.width, "x", extent.height, " frame by MIT-SHM: ", why);
        }
        const size_t row = static_cast<size_t>(extent.width) * 4;
        if (static_cast<size_t>(image_->bytes_per_line) == row)
            std::memcpy(image_->data, pixels, row * extent.height);
        else
            for (std::uint32_t y = 0; y < extent.height; ++y)
                std::memcpy(image_->data + static_cast<size_t>(y) * image_->bytes_per_line, pixels + y * row, row);
        XShmPutImage(display_, window_, gc_, image_, 0, 0, 0, 0, extent.width, extent.height, False);
        // The server has copied the segment once the round trip returns: the next frame may
        // overwrite it. (It also bounds the frames queued in the server to one.)
        XSync(display_, False);
    }

private:
    void detach()
    {
        if (attached_) {
            XShmDetach(display_, &segment_);
            XSync(display_, False);
            attached_ = false;
        }
        if (image_) {
            image_->data = nullptr; // the segment's, not Xlib's to free
            XDestroyImage(image_);
            image_ = nullptr;
        }
        if (segment_.shmaddr) {
            shmdt(segment_.shmaddr);
            segment_.shmaddr = nullptr;
        }
        segment_.shmid = -1;
        size_ = {};
    }

    Display* display_;
    ::Window window_; // Xlib's (an XID), not gui::Window
    Visual* visual_;
    int depth_;
    VkFormat format_;
    GC gc_ = nullptr;
    XImage* image_ = nullptr;
    XShmSegmentInfo segment_ {}; // shmid -1 (none) from the constructor
    bool attached_ = false;
    VkExtent2D size_ {};
};

} // namespace

std::unique_ptr<gpu::FrameSink> createX11ShmSink(GLFWwindow* window, VkExtent2D size, std::string& why)
{
    Display* display = glfwGetX11Display();
    if (!display) {
        why = "the window is not an X11 window";
        return nullptr;
    }
    if (!XShmQueryExtension(display)) {
        why = "the X server has no MIT-SHM";
        return nullptr;
    }
    const ::Window x = glfwGetX11Window(window);
    XWindowAttributes attributes {};
    if (!XGetWindowAttributes(display, x, &attributes)) {
        why = "cannot read the window's attributes";
        return nullptr;
    }
    const Visual* v = attributes.visual;
    // With 32-bit pixels in the server's byte order LSBFirst (XShmCreateImage uses the server's),
    // a red mask of 0xff0000 puts the bytes in
    // memory as B, G, R, X: Vulkan's B8G8R8A8; 0xff puts them as R, G, B, X.
    VkFormat format = VK_FORMAT_UNDEFINED;
    const bool lsbFirst = ImageByteOrder(display) == LSBFirst;
    if (v->c_class == TrueColor && lsbFirst && v->green_mask == 0xff00) {
        if (v->red_mask == 0xff0000 && v->blue_mask == 0xff)
            format = VK_FORMAT_B8G8R8A8_UNORM;
        else if (v->red_mask == 0xff && v->blue_mask == 0xff0000)
            format = VK_FORMAT_R8G8B8A8_UNORM;
    }
    if (format == VK_FORMAT_UNDEFINED) {
        why = "the window's visual is not 8-bit RGB TrueColor with the server's pixels least significant byte first";
        return nullptr;
    }
    auto sink = std::make_unique<X11ShmSink>(display, x, attributes.visual, attributes.depth, format);
    if (size.width > 0 && size.height > 0 && !sink->attach(size, why))
        return nullptr;
    return sink;
}

} // namespace facesketch::gui

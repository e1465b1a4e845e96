#pragma once
// Navigation as in Blender, on an OrbitView (geometry/camera.h), and the pointer's state machine
// that turns mouse input into strokes and view changes. No window here: the app feeds GLFW's
// events in framebuffer pixels (x right, y down, the stroke convention of sketch/stroke.h).
//
//   left drag            draw a stroke (read on release)
//   middle or right drag orbit: 0.4 degrees of azimuth/elevation per pixel
//   shift + middle drag  pan: the point under the cursor stays under it
//   wheel                zoom: each step scales the visible height by 0.9 (in) or 1/0.9 (out)
//   1 / 3 / 7            front / profile / three-quarter (keeps target and zoom)
//   Home                 reset to the view framing the face
//   5                    perspective <-> orthographic (the same visible height at the target)

#include "geometry/camera.h"
#include "sketch/stroke.h"

#include <optional>

namespace facesketch::gui {

class Navigator {
public:
    /// `home` is the view reset() returns to (its size is the viewport's).
    explicit Navigator(const OrbitView& home);

    const OrbitView& view() const { return view_; }
    const OrbitView& home() const { return home_; }

    /// Turns the view by a drag of (dx, dy) pixels: right turns the face to the right (azimuth
    /// decreases), down looks from higher up (elevation increases, clamped to +-89 degrees).
    /// Azimuth is kept in (-180, 180].
    void orbit(double dxPx, double dyPx);
    /// Moves the target in the view plane so that the scene follows a drag of (dx, dy) pixels.
    void pan(double dxPx, double dyPx);
    /// Zooms by `steps` wheel steps (positive: in).
    void zoom(double steps);
    /// The preset of a number key: '1' front (0, 0), '3' profile (90, 0), '7' three-quarter
    /// (45, 0); returns false for any other key (view unchanged).
    bool preset(char key);
    /// Back to the home view (in the current viewport size and projection).
    void reset();
    /// Switches orthographic <-> perspective keeping the visible height at the target.
    void toggleProjection();
    void setProjection(Projection kind);
    /// A new viewport size (pixels); the visible height stays, the width follows the aspect.
    /// Sizes below 1 are ignored (a minimised window).
    void resize(int width, int height);

    /// Millimetres per pixel at the target.
    double mmPerPixel() const;

private:
    OrbitView home_, view_;
};

/// The pointer: which drag is in progress and the stroke being drawn.
class Pointer {
public:
    enum class Button { Left, Middle, Right };
    enum class Drag { None, Stroke, Orbit, Pan };

    /// A button pressed at (x, y) pixels at `timeMs`; `shift` held. Starts a drag unless one is
    /// in progress (a second button is ignored until the first is released).
    void press(Button button, bool shift, double x, double y, double timeMs, const OrbitView& view);
    /// The cursor moved; orbit and pan drags change `navigator`, a stroke grows.
    void move(double x, double y, double timeMs, Navigator& navigator);
    /// A button released: returns the finished stroke when it ends a stroke drag.
    std::optional<sketch::Stroke> release(Button button, double x, double y, double timeMs, Navigator& navigator);

    Drag drag() const { return drag_; }
    /// The stroke being drawn (valid while drag() == Stroke).
    const sketch::Stroke& stroke() const { return stroke_; }

private:
    Drag drag_ = Drag::None;
    Button button_ = Button::Left;
    double lastX_ = 0, lastY_ = 0, startMs_ = 0;
    sketch::Stroke stroke_;
};

} // namespace facesketch::gui

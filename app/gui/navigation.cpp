#include "gui/navigation.h"

#include <algorithm>
#include <cmath>

namespace facesketch::gui {

namespace {

constexpr double kDegreesPerPixel = 0.4;
constexpr double kZoomStep = 0.9;

} // namespace

Navigator::Navigator(const OrbitView& home)
    : home_(home)
    , view_(home)
{
    orbitCamera(home); // validates
}

double Navigator::mmPerPixel() const
{
    const double halfHeight = view_.kind == Projection::Orthographic ? view_.halfHeight : view_.distance * std::tan(view_.fovY / 2);
    return 2 * halfHeight / view_.height;
}

void Navigator::orbit(double dxPx, double dyPx)
{
    double az = view_.angles.azimuthDeg - kDegreesPerPixel * dxPx;
    az = std::remainder(az, 360.0);
    if (az <= -180)
        az += 360;
    view_.angles.azimuthDeg = az;
    view_.angles.elevationDeg = std::clamp(view_.angles.elevationDeg + kDegreesPerPixel * dyPx, -89.0, 89.0);
}

void Navigator::pan(double dxPx, double dyPx)
{
    const Camera c = orbitCamera(view_);
    // The rows of the world-to-eye rotation are the camera's right and up axes.
    const glm::dvec3 right(c.view[0][0], c.view[1][0], c.view[2][0]);
    const glm::dvec3 up(c.view[0][1], c.view[1][1], c.view[2][1]);
    const double s = mmPerPixel();
    view_.target += -right * (dxPx * s) + up * (dyPx * s);
}

void Navigator::zoom(double steps)
{
    const double f = std::pow(kZoomStep, steps);
    if (view_.kind == Projection::Orthographic) {
        view_.halfHeight = std::clamp(view_.halfHeight * f, 1.0, 5000.0);
    } else {
        // Not closer than twice the near plane, not beyond the far plane's reach.
        view_.distance = std::clamp(view_.distance * f, 2 * view_.nearPlane, 0.9 * view_.farPlane);
    }
}

bool Navigator::preset(char key)
{
    switch (key) {
    case '1':
        view_.angles = { 0, 0 };
        return true;
    case '3':
        view_.angles = { 90, 0 };
        return true;
    case '7':
        view_.angles = { 45, 0 };
        return true;
    default:
        return false;
    }
}

void Navigator::reset()
{
    const int w = view_.width, h = view_.height;
    const Projection kind = view_.kind;
    view_ = home_;
    view_.width = w;
    view_.height = h;
    // The home view's visible height, in this projection.
    const double halfHeight = home_.kind == Projection::Orthographic ? home_.halfHeight : home_.distance * std::tan(home_.fovY / 2);
    view_.halfHeight = halfHeight;
    view_.kind = home_.kind;
    setProjection(kind);
}

void Navigator::setProjection(Projection kind)
{
    if (kind == view_.kind)
        return;
    const double t = std::tan(view_.fovY / 2);
    if (kind == Projection::Perspective) {
        view_.distance = std::clamp(view_.halfHeight / t, 2 * view_.nearPlane, 0.9 * view_.farPlane);
    } else {
        view_.halfHeight = view_.distance * t;
    }
    view_.kind = kind;
}

void Navigator::toggleProjection()
{
    setProjection(view_.kind == Projection::Orthographic ? Projection::Perspective : Projection::Orthographic);
}

void Navigator::resize(int width, int height)
{
    if (width < 1 || height < 1)
        return;
    view_.width = width;
    view_.height = height;
    home_.width = width;
    home_.height = height;
}

void Pointer::press(Button button, bool shift, double x, double y, double timeMs, const OrbitView& view)
{
    if (drag_ != Drag::None)
        return;
    button_ = button;
    lastX_ = x;
    lastY_ = y;
    if (button == Button::Left) {
        drag_ = Drag::Stroke;
        startMs_ = timeMs;
        stroke_ = {};
        stroke_.view = view;
        stroke_.points.push_back({ x, y, 0.0 });
    } else if (button == Button::Middle && shift) {
        drag_ = Drag::Pan;
    } else {
        drag_ = Drag::Orbit;
    }
}

void Pointer::move(double x, double y, double timeMs, Navigator& navigator)
{
    const double dx = x - lastX_, dy = y - lastY_;
    switch (drag_) {
    case Drag::None:
        break;
    case Drag::Stroke:
        // Repeated positions add nothing to a stroke; time must not go backwards.
        if (dx != 0 || dy != 0)
            stroke_.points.push_back({ x, y, std::max(timeMs - startMs_, *stroke_.points.back().timeMs) });
        break;
    case Drag::Orbit:
        navigator.orbit(dx, dy);
        break;
    case Drag::Pan:
        navigator.pan(dx, dy);
        break;
    }
    lastX_ = x;
    lastY_ = y;
}

std::optional<sketch::Stroke> Pointer::release(Button button, double x, double y, double timeMs, Navigator& navigator)
{
    if (drag_ == Drag::None || button != button_)
        return std::nullopt;
    move(x, y, timeMs, navigator);
    const Drag was = drag_;
    drag_ = Drag::None;
    if (was != Drag::Stroke)
        return std::nullopt;
    return std::move(stroke_);
}

} // namespace facesketch::gui

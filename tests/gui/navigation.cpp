// Blender-like navigation on an OrbitView and the pointer's drags.
#include "gui/navigation.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::gui;

namespace {

OrbitView home()
{
    return frameSphereView({ 0, 10, 20 }, 100, { 0, 0 }, 800, 600);
}

} // namespace

TEST_CASE("navigation: orbit turns by 0.4 degrees per pixel, wraps azimuth and clamps elevation")
{
    Navigator n(home());
    n.orbit(-100, 0);
    REQUIRE(n.view().angles.azimuthDeg == Approx(40));
    n.orbit(0, 50);
    REQUIRE(n.view().angles.elevationDeg == Approx(20));
    n.orbit(-400, 0); // 40 + 160 = 200 -> -160
    REQUIRE(n.view().angles.azimuthDeg == Approx(-160));
    n.orbit(0, 10000);
    REQUIRE(n.view().angles.elevationDeg == Approx(89));
    REQUIRE(n.view().target == home().target);
}

TEST_CASE("navigation: pan keeps the point under the cursor under it, in both projections")
{
    for (Projection kind : { Projection::Orthographic, Projection::Perspective }) {
        Navigator n(home());
        n.setProjection(kind);
        n.orbit(-80, 30);
        const glm::dvec3 target = n.view().target;
        const glm::dvec3 before = orbitCamera(n.view()).project(target);
        n.pan(37, -21);
        const glm::dvec3 after = orbitCamera(n.view()).project(target);
        REQUIRE(after.x == Approx(before.x + 37).margin(1e-6));
        REQUIRE(after.y == Approx(before.y - 21).margin(1e-6));
    }
}

TEST_CASE("navigation: the wheel zooms, presets keep target and zoom, reset frames the face again")
{
    Navigator n(home());
    const double h = n.view().halfHeight;
    n.zoom(2);
    REQUIRE(n.view().halfHeight == Approx(h * 0.81));
    n.zoom(-1);
    REQUIRE(n.view().halfHeight == Approx(h * 0.9));
    n.pan(10, 10);
    const glm::dvec3 target = n.view().target;
    REQUIRE(n.preset('3'));
    REQUIRE(n.view().angles.azimuthDeg == 90);
    REQUIRE(n.preset('7'));
    REQUIRE(n.view().angles.azimuthDeg == 45);
    REQUIRE(n.preset('1'));
    REQUIRE(n.view().angles.azimuthDeg == 0);
    REQUIRE_FALSE(n.preset('2'));
    REQUIRE(n.view().target == target);
    REQUIRE(n.view().halfHeight == Approx(h * 0.9));
    n.resize(1000, 500);
    n.reset();
    REQUIRE(n.view().target == home().target);
    REQUIRE(n.view().halfHeight == Approx(h));
    REQUIRE(n.view().width == 1000);
    REQUIRE(n.view().height == 500);
    n.resize(0, 0); // minimised: ignored
    REQUIRE(n.view().width == 1000);
}

TEST_CASE("navigation: switching the projection keeps the visible height at the target")
{
    Navigator n(home());
    const glm::dvec3 edge = n.view().target + glm::dvec3(0, 40, 0);
    const double y0 = orbitCamera(n.view()).project(edge).y;
    n.toggleProjection();
    REQUIRE(n.view().kind == Projection::Perspective);
    REQUIRE(orbitCamera(n.view()).project(edge).y == Approx(y0).epsilon(1e-9));
    n.zoom(3);
    const double y1 = orbitCamera(n.view()).project(edge).y;
    n.toggleProjection();
    REQUIRE(n.view().kind == Projection::Orthographic);
    REQUIRE(orbitCamera(n.view()).project(edge).y == Approx(y1).epsilon(1e-9));
}

TEST_CASE("pointer: left drags draw strokes in the view they began in, middle and right drags navigate")
{
    Navigator n(home());
    Pointer p;
    p.press(Pointer::Button::Left, false, 100, 200, 1000, n.view());
    REQUIRE(p.drag() == Pointer::Drag::Stroke);
    p.move(110, 205, 1016, n);
    p.move(110, 205, 1020, n);                                    // no movement: no point
    p.press(Pointer::Button::Right, false, 0, 0, 1030, n.view()); // ignored during a stroke
    p.move(120, 207, 1033, n);
    REQUIRE_FALSE(p.release(Pointer::Button::Right, 0, 0, 1040, n));
    const auto stroke = p.release(Pointer::Button::Left, 130, 210, 1050, n);
    REQUIRE(stroke);
    REQUIRE(stroke->points.size() == 4);
    REQUIRE(stroke->points[0].x == 100);
    REQUIRE(*stroke->points[0].timeMs == 0);
    REQUIRE(stroke->points[3].y == 210);
    REQUIRE(*stroke->points[3].timeMs == 50);
    REQUIRE(stroke->view.angles.azimuthDeg == home().angles.azimuthDeg);
    REQUIRE(n.view().angles.azimuthDeg == 0); // drawing never moves the view
    REQUIRE(p.drag() == Pointer::Drag::None);

    p.press(Pointer::Button::Middle, false, 0, 0, 0, n.view());
    REQUIRE(p.drag() == Pointer::Drag::Orbit);
    p.move(-50, 0, 5, n);
    REQUIRE_FALSE(p.release(Pointer::Button::Middle, -50, 0, 6, n));
    REQUIRE(n.view().angles.azimuthDeg == Approx(20));

    p.press(Pointer::Button::Right, false, 0, 0, 0, n.view());
    REQUIRE(p.drag() == Pointer::Drag::Orbit);
    p.release(Pointer::Button::Right, 0, 10, 1, n);
    REQUIRE(n.view().angles.elevationDeg == Approx(4));

    const glm::dvec3 target = n.view().target;
    p.press(Pointer::Button::Middle, true, 0, 0, 0, n.view());
    REQUIRE(p.drag() == Pointer::Drag::Pan);
    p.release(Pointer::Button::Middle, 10, 0, 1, n);
    REQUIRE(n.view().target != target);
    REQUIRE(n.view().angles.azimuthDeg == Approx(20));
}

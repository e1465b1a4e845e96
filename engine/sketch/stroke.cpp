#include "sketch/stroke.h"

#include "core/error.h"

#include <cmath>

namespace facesketch::sketch {

const char* surfaceName(Surface surface)
{
    switch (surface) {
    case Surface::Face:
        return "face";
    case Surface::FrontPlane:
        return "front-plane";
    case Surface::ProfilePlane:
        return "profile-plane";
    case Surface::Paper:
        return "paper";
    }
    return "unknown";
}

Surface parseSurface(const std::string& text)
{
    for (Surface s : { Surface::Face, Surface::FrontPlane, Surface::ProfilePlane, Surface::Paper })
        if (text == surfaceName(s))
            return s;
    fail("surface '", text, "' is none of face, front-plane, profile-plane, paper");
}

void validateStroke(const Stroke& stroke, const std::string& what)
{
    if (stroke.points.empty())
        fail(what, ": the stroke has no points");
    // The last point before i that had a time: times need not be given for every point, but
    // the ones given must not go backwards.
    std::optional<std::size_t> lastTimed;
    for (std::size_t i = 0; i < stroke.points.size(); ++i) {
        const StrokePoint& p = stroke.points[i];
        if (!std::isfinite(p.x))
            fail(what, ": point ", i, " has x = ", p.x, ", not a finite number");
        if (!std::isfinite(p.y))
            fail(what, ": point ", i, " has y = ", p.y, ", not a finite number");
        if (p.timeMs) {
            if (!std::isfinite(*p.timeMs))
                fail(what, ": point ", i, " has time ", *p.timeMs, " ms, not a finite number");
            if (lastTimed && *p.timeMs < *stroke.points[*lastTimed].timeMs)
                fail(what, ": point ", i, " has time ", *p.timeMs, " ms, before point ", *lastTimed, "'s ",
                    *stroke.points[*lastTimed].timeMs, " ms");
            lastTimed = i;
        }
    }
    try {
        (void)orbitCamera(stroke.view);
    } catch (const Error& e) {
        fail(what, ": ", e.what());
    }
    const glm::dvec3& t = stroke.view.target;
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z))
        fail(what, ": view target (", t.x, ", ", t.y, ", ", t.z, ") is not finite");
    if (!std::isfinite(stroke.view.angles.azimuthDeg) || !std::isfinite(stroke.view.angles.elevationDeg))
        fail(what, ": view angles (", stroke.view.angles.azimuthDeg, ", ", stroke.view.angles.elevationDeg, ") are not finite");
}

} // namespace facesketch::sketch

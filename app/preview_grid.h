#pragma once
// The preview grid shared by `facesketch preview` (any dataset) and `facesketch synth
// --preview` (the generator's faces and poses): one row of cells per up to 8 faces, each face
// drawn front (upper cell) above profile (lower cell) on white, rendered offscreen.

#include "geometry/camera.h"
#include "render/renderer.h"

#include <functional>
#include <string>

namespace facesketch::app {

/// Writes a PNG of `count` faces (count >= 1) in cells of `cell` x `cell` pixels:
/// min(count, 8) columns, views * ceil(count / columns) rows of cells. For face i the renderer
/// is cleared, `addFace(renderer, i)` adds its meshes, and it is drawn with `camera(0)` (front)
/// into the upper cell, `camera(1)` (profile) below it, and so on for `views` (>= 1) cameras.
/// The device is headless (gpu::ScopedDevice). Throws Error if the PNG cannot be written.
void writePreviewGrid(const std::string& path, int count, int cell, const std::function<void(Renderer& renderer, int face)>& addFace,
    const std::function<Camera(int view)>& camera, int views = 2);

} // namespace facesketch::app

#pragma once
// The offscreen renderer: draws lit, smooth-shaded triangle meshes, coloured lines and points
// into an RGBA image (4x MSAA resolved), for previews, screenshots and headless checks. It is one
// user of SceneRenderer (render/scene_renderer.h): its own colour, depth and resolve images and
// render pass, the scene recorded into them, and a readback that waits on the fence of its own
// submission only.
//
//   gpu::Device device = gpu::createDevice({});
//   Renderer renderer(device, 800, 800);
//   renderer.addMesh(mesh);                       // grey, normals computed on the CPU
//   Image image = renderer.render(frameMesh(mesh, parseView("front"), 800, 800));
//   writePng("out.png", image);

#include "core/mesh.h"
#include "geometry/camera.h"
#include "gpu/device.h"
#include "io/png.h"
#include "render/scene_renderer.h"

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace facesketch {

class Renderer {
public:
    /// An offscreen target of width x height pixels with `samples` MSAA samples (1 or 4).
    Renderer(gpu::Device& device, int width, int height, int samples = 4);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    int width() const;
    int height() const;

    /// A mesh with area-weighted vertex normals; `colors`, if non-empty, is #V RGBA in [0, 1].
    void addMesh(const Mesh& mesh, const MeshStyle& style = {}, const std::vector<glm::vec4>& colors = {});
    /// Line segments: points[2i], points[2i+1]; colours one per point or one for all.
    void addLines(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors);
    /// Round points of `size` pixels; colours one per point or one for all.
    void addPoints(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors, float size = 3.0f);
    /// Removes every draw item.
    void clear();

    /// The scene drawn by render(): for what the calls above do not cover (updateMesh, screen
    /// polylines, the overlay, hiding items). Items added there and here are one scene.
    SceneRenderer& scene();

    /// Draws all items seen by `camera` (whose width/height must match) over `background`, and
    /// waits for this submission's fence (not for the device) to read the image back.
    Image render(const Camera& camera, glm::vec4 background = { 1, 1, 1, 1 });

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace facesketch

#pragma once
// The real-time renderer: a retained scene of draw items (lit meshes, world-space lines and
// points, screen-space polylines in pixels, one full-viewport RGBA overlay) kept in GPU buffers,
// recorded by record() into a pass the caller has begun. The window (a swapchain image) and the
// offscreen Renderer (render/renderer.h, PNGs) are two users of it.
//
//   SceneRenderer scene(device, { .color = swapchain.format, .samples = 4 });   // dynamic rendering
//   DrawId face = scene.addMesh(mesh);                 // uploaded once
//   ...
//   scene.updateMesh(face, newV);                      // a stroke moved the vertices: same topology
//   // per frame, after FrameLoop::beginFrame (the slot's previous frame has finished):
//   //   begin rendering (colour + depth attachments of the formats above, viewport-sized)
//   scene.record(frame.cmd, frame.slot, camera, frame.extent);
//   //   end rendering
//
// Frames in flight: each item's GPU copy exists once per slot (0 .. slots-1), and record(cmd,
// slot, ...) writes the slot's copy when the item changed since that slot last drew it. The
// caller must only record into `slot` once the GPU has finished the previous submission that
// used `slot` (FrameLoop::beginFrame waits for exactly that fence). So edits never wait for the
// GPU, and removed items are destroyed once every slot has been recorded again.
//
// Draw order: every depth-tested item in the order added, then the overlay, then every item
// without depth test (screen polylines, LineStyle::depthTest = false) in the order added.
// Blending: colour = src.rgb * src.a + dst.rgb * (1 - src.a), alpha = src.a + dst.a * (1 - src.a).
// A mesh whose colours all have alpha 1 is drawn without blending (the same result, and a
// software rasteriser then need not read back the samples it covers).
// Colours are written as given (linear values into a UNORM target, as in the PNGs).

#include "core/mesh.h"
#include "geometry/camera.h"
#include "gpu/device.h"
#include "io/png.h"

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace facesketch {

struct MeshStyle {
    glm::vec4 color { 0.78f, 0.72f, 0.68f, 1.0f }; ///< used when no per-vertex colours are given
    bool lit = true;                               ///< Lambert + soft specular from a head light
};

struct LineStyle {
    float width = 1.0f;    ///< pixels; widths above 1 need the wideLines feature (else drawn 1 wide)
    bool depthTest = true; ///< false: drawn on top of everything, after the overlay
};

/// What record() draws into, fixed at construction (the pipelines are built for it).
struct RenderTargetFormat {
    VkFormat color = VK_FORMAT_R8G8B8A8_UNORM;
    VkFormat depth = VK_FORMAT_D32_SFLOAT; ///< the pass must have a depth attachment of this format
    int samples = 4;                       ///< 1 or 4 (MSAA), of both attachments
    /// VK_NULL_HANDLE: record() runs inside vkCmdBeginRendering (dynamic rendering; needs
    /// Device::beginRendering). Otherwise inside `subpass` of a render pass compatible with
    /// `renderPass` (one colour attachment and one depth attachment of the formats above).
    VkRenderPass renderPass = VK_NULL_HANDLE;
    std::uint32_t subpass = 0;
};

/// Names one draw item of a SceneRenderer; never reused within one renderer.
using DrawId = std::uint32_t;

class SceneRenderer {
public:
    /// Pipelines for `target`, per-item GPU copies for `slots` frames in flight (1 for a renderer
    /// that waits for each submission, gpu::framesInFlight for a window). Throws Error for a bad
    /// sample count or slot count, or dynamic rendering asked of a device without it.
    SceneRenderer(gpu::Device& device, const RenderTargetFormat& target, std::uint32_t slots);
    /// The GPU must have finished every submission that recorded this renderer.
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    /// The constructor's target (record()'s target 0).
    const RenderTargetFormat& target() const;
    /// Another target record() may draw into, e.g. a one-sample pass for the frames drawn while
    /// a view moves beside the 4x MSAA one; returns its index for record(). The items are shared;
    /// pipelines are built per target on first use. Throws Error as the constructor does.
    std::uint32_t addTarget(const RenderTargetFormat& target);
    std::uint32_t slots() const;

    /// A triangle mesh with area-weighted vertex normals (computed on the CPU). `colors`, if
    /// non-empty, is #V RGBA in [0, 1] and replaces style.color. The triangles are uploaded once.
    DrawId addMesh(const Mesh& mesh, const MeshStyle& style = {}, const std::vector<glm::vec4>& colors = {});
    /// New vertex positions for a mesh, same topology: `V` is #V by 3 (mm), #V as at addMesh.
    /// Normals are recomputed. Throws Error on a count mismatch or a non-finite value.
    void updateMesh(DrawId mesh, const Vertices& V);
    /// Per-vertex colours (#V RGBA), or empty for the style's colour (e.g. to flash vertices).
    void setMeshColors(DrawId mesh, const std::vector<glm::vec4>& colors);
    void setMeshStyle(DrawId mesh, const MeshStyle& style);

    /// World-space line segments (mm): points[2i], points[2i+1]; colours one per point or one
    /// for all. Drawn with a small depth offset towards the camera so lines on a surface show.
    DrawId addLines(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors, const LineStyle& style = {});
    /// World-space round points of `size` pixels (1 without the largePoints feature).
    DrawId addPoints(const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors, float size = 3.0f);
    /// A polyline in pixels of the target (x right, y down, origin at the top-left corner, pixel
    /// centres at +0.5), e.g. the stroke being drawn; consecutive points are joined. Never depth
    /// tested: drawn over everything. Colours one per point or one for all.
    DrawId addScreenPolyline(const std::vector<glm::vec2>& pixels, const std::vector<glm::vec4>& colors, float width = 1.0f);
    /// Replace the geometry of an item made by addLines / addPoints / addScreenPolyline (same
    /// kind; the style stays). Throws Error for another kind of item.
    void setLines(DrawId lines, const std::vector<glm::vec3>& points, const std::vector<glm::vec4>& colors);
    void setPoints(DrawId points, const std::vector<glm::vec3>& positions, const std::vector<glm::vec4>& colors);
    void setScreenPolyline(DrawId polyline, const std::vector<glm::vec2>& pixels, const std::vector<glm::vec4>& colors);

    /// The full-viewport overlay: an RGBA image (any size; stretched over the viewport, nearest
    /// texel, row 0 at the top) blended over the depth-tested items with its alpha. One overlay
    /// per renderer; setOverlay replaces it, clearOverlay removes it.
    void setOverlay(const Image& rgba);
    void clearOverlay();

    /// Hidden items keep their GPU data and are skipped by record().
    void setVisible(DrawId item, bool visible);
    /// Removes an item (its GPU copies are destroyed once no frame in flight can use them).
    void remove(DrawId item);
    /// Removes every item and the overlay.
    void clear();

    /// Records the draws seen by `camera` into the pass begun on `cmd` (dynamic rendering or
    /// the render pass of target()), with viewport and scissor covering `extent` pixels. Writes
    /// the changed items into the copies of `slot` first (host writes: no commands recorded
    /// outside the pass). `camera` maps world to clip space; its width/height are not used.
    /// `pixelScale` is the target's pixels per pixel of the caller's coordinates: below 1 when
    /// the caller draws a reduced-resolution copy of its view (e.g. 0.5 while the view moves),
    /// so that screen polylines (given in the caller's pixels) land where they belong and
    /// line widths and point sizes shrink with the image (never below 1 pixel). `target`: 0 for
    /// the constructor's, or an index from addTarget(); the pass begun must be of that target.
    void record(VkCommandBuffer cmd, std::uint32_t slot, const Camera& camera, VkExtent2D extent, float pixelScale = 1.0f,
        std::uint32_t target = 0);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace facesketch

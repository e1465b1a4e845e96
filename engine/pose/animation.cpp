#include "pose/animation.h"

#include "core/error.h"
#include "geometry/normals.h"
#include "gpu/device.h"
#include "io/png.h"
#include "render/renderer.h"

#include <cstdio>

namespace facesketch::pose {

GltfAnimation timelineAnimation(const PoseModel& model, const Timeline& timeline, const Mesh& neutral, const std::vector<double>& times)
{
    if (times.empty())
        fail("animation: no frame times");
    TimelinePlayer player(model, timeline, neutral);
    GltfAnimation animation;
    animation.face = neutral;
    animation.faceNormals = vertexNormals(neutral);
    Mesh frame = neutral;
    for (double t : times) {
        player.frame(t, frame.V);
        animation.times.push_back(t);
        animation.frames.push_back(frame.V);
        animation.frameNormals.push_back(vertexNormals(frame));
    }
    return animation;
}

void writeFramePngs(const GltfAnimation& animation, const std::filesystem::path& folder, int size)
{
    validateGltfAnimation(animation);
    if (std::filesystem::exists(folder) && !(std::filesystem::is_directory(folder) && std::filesystem::is_empty(folder)))
        fail(folder.string(), ": exists and is not an empty folder; frames are written into a new one");
    std::filesystem::create_directories(folder);
    gpu::ScopedDevice deviceOwner;
    Renderer renderer(*deviceOwner, size, size);
    const Camera camera = frameMesh(animation.face, parseView("front"), size, size);
    for (std::size_t k = 0; k < animation.frames.size(); ++k) {
        renderer.clear();
        renderer.addMesh({ animation.frames[k], animation.face.F });
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04zu.png", k);
        writePng(folder / name, renderer.render(camera));
    }
}

} // namespace facesketch::pose

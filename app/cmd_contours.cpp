// `facesketch contours`: the contours of a face and the candidate cloud of a dataset from one
// view, as pictures (thesis figures 4.9, 4.14-4.17).

#include "commands.h"

#include "contours/candidates_gpu.h"
#include "contours/contour_lines.h"
#include "contours/curvature_cache.h"
#include "contours/curvature_gpu.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "dataset/dataset.h"
#include "geometry/mesh_batch.h"
#include "io/mesh_io.h"
#include "render/colormap.h"
#include "render/renderer.h"

#include <filesystem>
#include <iostream>
#include <map>

namespace facesketch::app {

namespace {

struct Faces {
    std::vector<Mesh> meshes;         // the faces whose contours form the cloud
    Mesh shown;                       // the face drawn with its contour lines (the mean face for a dataset)
    std::vector<std::uint32_t> flags; // VertexFlag per vertex
    std::map<std::string, std::vector<int>> labelled;
};

// A dataset's train and contour faces (the thesis' cached set, 4.4), skin only: the other
// components (eyes, teeth, tongue) are excluded from the contours, as are the manifest's
// excluded vertices (4.3.3).
Faces loadFaces(const std::filesystem::path& input, int maxFaces)
{
    Faces f;
    if (!std::filesystem::is_directory(input)) {
        f.shown = readMesh(input);
        f.meshes = { f.shown };
        return f;
    }
    const dataset::Dataset d = dataset::openDataset(input);
    const dataset::Manifest& m = d.manifest;
    for (const dataset::Sample& s : m.samples)
        if ((s.role == dataset::Role::Train || s.role == dataset::Role::Contour) && static_cast<int>(f.meshes.size()) < maxFaces)
            f.meshes.push_back(dataset::loadMesh(d, s.file));
    if (f.meshes.empty())
        fail(input.string(), ": no train or contour samples");
    f.flags.assign(m.vertexCount, VertexExcluded);
    if (const dataset::Component* skin = m.component("skin"))
        for (int v = skin->begin; v < skin->end; ++v)
            f.flags[v] = 0;
    for (const auto& [name, path] : m.contours)
        for (int v : path)
            f.flags[v] |= VertexLabelled;
    for (int v : m.excluded)
        f.flags[v] |= VertexExcluded;
    f.labelled = m.contours;
    f.shown = f.meshes[0];
    f.shown.V.setZero();
    for (const Mesh& mesh : f.meshes)
        f.shown.V += mesh.V;
    f.shown.V /= static_cast<double>(f.meshes.size());
    return f;
}

const glm::vec4 silhouetteColour { 0.05f, 0.05f, 0.05f, 1 }, suggestiveColour { 0.1f, 0.35f, 0.85f, 1 },
    labelledColour { 0.8f, 0.2f, 0.1f, 1 };

void addLines(Renderer& r, const ContourLines& lines)
{
    r.addLines(lines.silhouette, { silhouetteColour });
    r.addLines(lines.suggestive, { suggestiveColour });
    r.addLines(lines.labelled, { labelledColour });
}

} // namespace

void addContoursCommand(CLI::App& root)
{
    auto o = std::make_shared<ContourPictureOptions>();
    auto* cmd = root.add_subcommand("contours", "Draw a face's contours and a dataset's candidate cloud and its density from one view");
    cmd->add_option("input", o->input, "Dataset folder (its train and contour faces) or one mesh file")->required();
    cmd->add_option("-o,--output", o->output, "Prefix of the PNGs: PREFIX-face.png, -sketch.png, -cloud.png, -density.png")
        ->capture_default_str();
    cmd->add_option("--view", o->view, "front, profile, 34 (three-quarter) or AZ,EL in degrees")->capture_default_str();
    cmd->add_option("--size", o->size, "Image width and height in pixels")->capture_default_str()->check(CLI::Range(64, 8192));
    cmd->add_option("--faces", o->maxFaces, "At most this many faces in the cloud")->capture_default_str()->check(CLI::Range(1, 100000));
    cmd->add_option("--suggestive", o->suggestive, "Suggestive contour threshold on D_w k_r l^2")->capture_default_str();
    cmd->add_option("--rtsc", o->rtsc,
           "Suggestive contours by rtsc's filter instead, with this threshold on tan(theta) D_w k_r l^2 at the zero crossing (rtsc: "
           "0.01)")
        ->check(CLI::Range(0.0, 1e6));
    cmd->add_option("--silhouette", o->silhouette, "Silhouette threshold on |n.v| (default: 0.14 sqrt(863 / #V))");
    cmd->add_flag("--perspective", o->perspective, "Perspective instead of orthographic projection");
    cmd->add_flag("--no-cache", o->noCache,
        "Compute the curvature of the faces even if the cache ($FACESKETCH_CACHE_DIR, else "
        "$XDG_CACHE_HOME/facesketch or ~/.cache/facesketch) holds it, and do not write it");
    cmd->callback([o] { writeContourPictures(*o); });
}

void writeContourPictures(const ContourPictureOptions& options)
{
    const ContourPictureOptions* o = &options;
    {
        const ViewAngles view = parseView(o->view);
        Stopwatch clock;
        const Faces faces = loadFaces(o->input, o->maxFaces);
        const Eigen::Index nv = faces.shown.V.rows();
        const Camera camera
            = frameMesh(faces.shown, view, o->size, o->size, o->perspective ? Projection::Perspective : Projection::Orthographic);
        ContourParams params;
        params.silhouetteThreshold = o->silhouette >= 0 ? o->silhouette : defaultSilhouetteThreshold(nv);
        params.suggestiveThreshold = o->suggestive;
        if (o->rtsc >= 0) {
            params.suggestiveFilter = SuggestiveFilter::RtscCrossing;
            params.rtscThreshold = o->rtsc;
        }
        params.featureSize = meanEdgeLength(faces.shown);
        std::cout << "loaded " << faces.meshes.size() << " faces of " << nv << " vertices in " << clock.seconds() << " s\n";

        const Curvature curvature = estimateCurvature(faces.shown);
        const ContourLines lines = contourLines(faces.shown, curvature, camera, params, faces.flags, faces.labelled);

        gpu::ScopedDevice deviceOwner;
        gpu::Device& device = *deviceOwner;
        {
            std::vector<Candidate> cloud;
            {
                GpuCurvature gpuCurvature(device, faces.shown.F, nv);
                const std::vector<float> positions = meshMajorPositions(faces.meshes);
                gpuCurvature.setPositions(positions);
                const CachedCurvature pass = runCurvatureCached(
                    gpuCurvature, faces.shown.F, positions, o->noCache ? std::filesystem::path() : defaultCacheFolder());
                if (!pass.note.empty())
                    std::cerr << "warning: " << pass.note << "\n";
                GpuCandidates candidates(device, gpuCurvature, faces.flags);
                double cloudMs = 0;
                cloud = candidates.build(camera, params, &cloudMs);
                std::cout << "curvature of " << faces.meshes.size() << " faces: " << pass.milliseconds << " ms "
                          << (pass.restored ? "to read " + pass.file.string() : "on " + std::string(device.name)) << "; cloud of "
                          << cloud.size() << " candidates ("
                          << std::count_if(
                                 cloud.begin(), cloud.end(), [](const Candidate& c) { return (c.types & ContourSuggestive) != 0; })
                          << " suggestive): " << cloudMs << " ms\n";
            }
            Renderer r(device, o->size, o->size, 4);
            const std::string prefix = o->output;

            r.addMesh(faces.shown);
            addLines(r, lines);
            writePng(prefix + "-face.png", r.render(camera));

            r.clear();
            MeshStyle paper; // hides lines behind the face without drawing it
            paper.color = { 1, 1, 1, 1 };
            paper.lit = false;
            r.addMesh(faces.shown, paper);
            addLines(r, lines);
            writePng(prefix + "-sketch.png", r.render(camera));

            std::vector<glm::vec3> points;
            for (const Candidate& c : cloud)
                points.push_back({ c.world[0], c.world[1], c.world[2] });
            MeshStyle faint;
            faint.color = { 0.93f, 0.93f, 0.93f, 1 };
            r.clear();
            r.addMesh(faces.shown, faint);
            if (!points.empty())
                r.addPoints(points, { { 0.1f, 0.65f, 0.2f, 1 } }, 2.0f);
            writePng(prefix + "-cloud.png", r.render(camera));

            // Density: candidates per 4x4-pixel cell, log-scaled, blue (few) to red (many).
            const int cell = 4, cells = (o->size + cell - 1) / cell;
            std::vector<int> count(static_cast<size_t>(cells) * cells, 0);
            auto cellOf = [&](const Candidate& c) {
                const int x = std::clamp(static_cast<int>(c.screen[0]) / cell, 0, cells - 1);
                const int y = std::clamp(static_cast<int>(c.screen[1]) / cell, 0, cells - 1);
                return static_cast<size_t>(y) * cells + x;
            };
            for (const Candidate& c : cloud)
                ++count[cellOf(c)];
            const int most = count.empty() ? 1 : std::max(1, *std::max_element(count.begin(), count.end()));
            std::vector<glm::vec4> colours;
            for (const Candidate& c : cloud)
                colours.push_back(blueToRed(std::log(double(count[cellOf(c)])) / std::log(double(most) + 1e-9)));
            r.clear();
            r.addMesh(faces.shown, faint);
            if (!points.empty())
                r.addPoints(points, colours, 3.0f);
            writePng(prefix + "-density.png", r.render(camera));
            std::cout << "wrote " << prefix << "-face.png, -sketch.png, -cloud.png, -density.png (" << lines.silhouette.size() / 2
                      << " silhouette, " << lines.suggestive.size() / 2 << " suggestive, " << lines.labelled.size() / 2
                      << " labelled segments)\n";
        }
    }
}

} // namespace facesketch::app

// `facesketch preview`: a grid of a dataset's faces, front above profile (and three-quarter with --three-quarter), so a person can see at
// a glance what a synthetic or imported set looks like (any dataset; `synth --preview` adds the
// generator's own lip and brow colouring).

#include "commands.h"
#include "preview_grid.h"

#include "core/error.h"
#include "dataset/dataset.h"

#include <iostream>

namespace facesketch::app {

namespace {

glm::vec4 partColour(const std::string& component)
{
    if (component == "skin")
        return { 0.80f, 0.66f, 0.58f, 1 };
    if (component.rfind("eye", 0) == 0)
        return { 0.93f, 0.93f, 0.90f, 1 };
    if (component.rfind("teeth", 0) == 0)
        return { 0.95f, 0.93f, 0.85f, 1 };
    return { 0.75f, 0.40f, 0.42f, 1 }; // tongue, gums
}

struct PreviewOptions {
    std::string dataset, output;
    int count = 8, size = 320;
    bool threeQuarter = false; ///< a third row: the three-quarter view (parseView("34"): azimuth 45 degrees)
};

void writeDatasetPreview(const PreviewOptions& o)
{
    const dataset::Dataset d = dataset::openDataset(o.dataset);
    const int n = std::min<int>(o.count, static_cast<int>(d.manifest.samples.size()));
    if (n == 0)
        fail(o.dataset, ": no samples to preview");
    // One frame for every face (around the first face's skin), so sizes compare across the grid.
    Mesh first = dataset::loadMesh(d, d.manifest.samples[0].file);
    if (const dataset::Component* skin = d.manifest.component("skin"))
        first.V = first.V.middleRows(skin->begin, skin->size()).eval();
    auto addFace = [&](Renderer& renderer, int i) {
        const Mesh mesh = dataset::loadMesh(d, d.manifest.samples[static_cast<size_t>(i)].file);
        std::vector<glm::vec4> colours(static_cast<size_t>(mesh.V.rows()), partColour("other"));
        for (const dataset::Component& c : d.manifest.components)
            for (int v = c.begin; v < c.end; ++v)
                colours[static_cast<size_t>(v)] = partColour(c.name);
        renderer.addMesh(mesh, {}, colours);
    };
    auto camera = [&](int view) {
        const ViewAngles angles = view == 0 ? ViewAngles { 0, 0 } : view == 1 ? ViewAngles { 90, 0 } : parseView("34");
        return frameMesh(first, angles, o.size, o.size, Projection::Orthographic, 0.08);
    };
    writePreviewGrid(o.output, n, o.size, addFace, camera, o.threeQuarter ? 3 : 2);
    std::cout << "wrote " << o.output << " (" << n << " faces of " << o.dataset << ")\n";
}

} // namespace

void addPreviewCommand(CLI::App& root)
{
    auto o = std::make_shared<PreviewOptions>();
    auto* cmd = root.add_subcommand("preview", "Render a grid of a dataset's faces, front above profile, to a PNG");
    cmd->add_option("dataset", o->dataset, "Dataset folder")->required();
    cmd->add_option("-o,--output", o->output, "PNG file to write")->required();
    cmd->add_option("--count", o->count, "Faces in the grid (the first ones in the manifest)")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    cmd->add_option("--size", o->size, "Pixels per cell")->capture_default_str()->check(CLI::Range(64, 2048));
    cmd->add_flag("--three-quarter", o->threeQuarter, "Add a third row: the three-quarter view (azimuth 45 degrees, from the face's left)");
    cmd->callback([o] { writeDatasetPreview(*o); });
}

} // namespace facesketch::app

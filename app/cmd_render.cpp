#include "commands.h"

#include "core/error.h"
#include "io/mesh_io.h"
#include "render/renderer.h"

#include <iostream>

namespace facesketch::app {

void addRenderCommand(CLI::App& root)
{
    struct Options {
        std::string mesh, output, view = "front";
        int width = 1024, height = 1024, samples = 4;
        bool perspective = false;
    };
    auto o = std::make_shared<Options>();
    auto* cmd = root.add_subcommand("render", "Render an OBJ or PLY mesh, lit and smooth-shaded, to a PNG");
    cmd->add_option("mesh", o->mesh, "Mesh file (.obj or .ply)")->required();
    cmd->add_option("-o,--output", o->output, "PNG file to write")->required();
    cmd->add_option("--view", o->view, "front, profile, 34 (three-quarter) or AZ,EL in degrees")->capture_default_str();
    cmd->add_option("--width", o->width, "Image width in pixels")->capture_default_str()->check(CLI::Range(16, 16384));
    cmd->add_option("--height", o->height, "Image height in pixels")->capture_default_str()->check(CLI::Range(16, 16384));
    cmd->add_option("--samples", o->samples, "MSAA samples (1 or 4)")->capture_default_str()->check(CLI::IsMember({ 1, 4 }));
    cmd->add_flag("--perspective", o->perspective, "Perspective instead of orthographic projection");
    cmd->callback([o] {
        const ViewAngles view = parseView(o->view);
        const Mesh mesh = readMesh(o->mesh);
        gpu::ScopedDevice deviceOwner;
        gpu::Device& device = *deviceOwner;
        {
            Image image;
            {
                Renderer renderer(device, o->width, o->height, o->samples);
                renderer.addMesh(mesh);
                image = renderer.render(
                    frameMesh(mesh, view, o->width, o->height, o->perspective ? Projection::Perspective : Projection::Orthographic));
            }
            writePng(o->output, image);
        }
        std::cout << "wrote " << o->output << " (" << o->width << "x" << o->height << ", " << mesh.V.rows() << " vertices, "
                  << mesh.F.rows() << " triangles)\n";
    });
}

} // namespace facesketch::app

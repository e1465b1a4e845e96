#include "commands.h"

#include "core/error.h"
#include "geometry/primitives.h"
#include "io/png.h"
#include "render/renderer.h"

#include <iostream>

namespace facesketch::app {

void addDemoCommand(CLI::App& root)
{
    auto output = std::make_shared<std::string>("facesketch-demo.png");
    auto* cmd = root.add_subcommand("demo", "Render the built-in demo scene to a PNG (no input files needed)");
    cmd->add_option("-o,--output", *output, "PNG file to write")->capture_default_str();
    cmd->callback([output] {
        gpu::Device device = gpu::createDevice();
        Image image;
        try {
            const int size = 768;
            Renderer renderer(device, size, size, 4);
            Mesh sphere = makeIcosphere(60.0, 5);
            renderer.addMesh(sphere);
            // The sphere's equator and meridian as lines, and its icosahedron vertices as points:
            // the three primitive kinds every later preview uses.
            std::vector<glm::vec3> lines, points;
            for (int i = 0; i < 128; ++i) {
                const double a0 = 2 * M_PI * i / 128, a1 = 2 * M_PI * (i + 1) / 128;
                lines.push_back({60.5 * std::cos(a0), 0, 60.5 * std::sin(a0)});
                lines.push_back({60.5 * std::cos(a1), 0, 60.5 * std::sin(a1)});
                lines.push_back({0, 60.5 * std::cos(a0), 60.5 * std::sin(a0)});
                lines.push_back({0, 60.5 * std::cos(a1), 60.5 * std::sin(a1)});
            }
            const Mesh ico = makeIcosphere(60.5, 0);
            for (Eigen::Index v = 0; v < ico.V.rows(); ++v)
                points.push_back({ico.V(v, 0), ico.V(v, 1), ico.V(v, 2)});
            renderer.addLines(lines, {{0.1f, 0.3f, 0.8f, 1.0f}});
            renderer.addPoints(points, {{0.85f, 0.15f, 0.1f, 1.0f}}, 9.0f);
            image = renderer.render(frameMesh(sphere, {30, 20}, size, size, Projection::Perspective, 0.15));
        } catch (...) {
            gpu::destroyDevice(device);
            throw;
        }
        gpu::destroyDevice(device);
        writePng(*output, image);
        std::cout << "wrote " << *output << "\n";
    });
}

} // namespace facesketch::app

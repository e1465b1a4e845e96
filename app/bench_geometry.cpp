// Benchmarks of the geometry kernels and the renderer.

#include "bench.h"

#include "core/random.h"
#include "core/stopwatch.h"
#include "geometry/normals.h"
#include "geometry/normals_gpu.h"
#include "geometry/primitives.h"
#include "render/renderer.h"

#include <cmath>

namespace facesketch::app {

namespace {

// A batch of `meshes` distinct bumpy grids with about `vertices` vertices each, deterministic.
std::vector<float> bumpyBatch(const Mesh& grid, int meshes)
{
    Random random(20100101);
    std::vector<float> positions;
    positions.reserve(static_cast<size_t>(meshes) * grid.V.rows() * 3);
    for (int m = 0; m < meshes; ++m) {
        const double a = random.uniform(-1, 1), b = random.uniform(-1, 1), c = random.uniform(-1, 1);
        for (Eigen::Index v = 0; v < grid.V.rows(); ++v) {
            const double x = grid.V(v, 0), y = grid.V(v, 1);
            positions.push_back(static_cast<float>(x));
            positions.push_back(static_cast<float>(y));
            positions.push_back(static_cast<float>(10 * a * std::sin(0.05 * x + b) * std::cos(0.04 * y + c)));
        }
    }
    return positions;
}

} // namespace

void benchNormals(const BenchOptions& options, std::ostream& out)
{
    const int side = std::max(2, static_cast<int>(std::lround(std::sqrt(double(options.vertices)))));
    const Mesh grid = makeGrid(side, side, 150.0, 150.0);
    const std::vector<float> positions = bumpyBatch(grid, options.meshes);

    gpu::ScopedDevice deviceOwner;
    gpu::Device& device = *deviceOwner;
    out << "# device: " << device.name << (device.validation ? " (validation on: timings not representative)" : "") << "\n";
    out << "# batch: " << options.meshes << " meshes x " << grid.V.rows() << " vertices, " << grid.F.rows() << " triangles\n";
    {
        GpuNormals kernel(device, grid.F, grid.V.rows());
        Stopwatch upload;
        kernel.setPositions(positions);
        const double uploadMs = upload.milliseconds();
        kernel.run(); // warm-up: pipeline compilation on first use
        std::vector<double> gpuMs, wallMs;
        for (int r = 0; r < options.repeat; ++r) {
            Stopwatch wall;
            gpuMs.push_back(kernel.run());
            wallMs.push_back(wall.milliseconds());
        }
        Stopwatch download;
        const std::vector<float> normals = kernel.normals();
        const double downloadMs = download.milliseconds();
        out << "normals_gpu_ms " << median(gpuMs) << " ms\n";
        out << "normals_gpu_submit_wait_ms " << median(wallMs) << " ms\n";
        out << "normals_gpu_upload_ms " << uploadMs << " ms\n";
        out << "normals_gpu_readback_ms " << downloadMs << " ms\n";
    }
    std::vector<double> cpuMs;
    for (int r = 0; r < std::min(options.repeat, 5); ++r) {
        Stopwatch cpu;
        const std::vector<float> normals = vertexNormalsBatch(positions, grid.F, grid.V.rows());
        cpuMs.push_back(cpu.milliseconds());
    }
    out << "normals_cpu_1thread_ms " << median(cpuMs) << " ms\n";
}

void benchRender(const BenchOptions& options, std::ostream& out)
{
    const Mesh sphere = makeIcosphere(1.0, 5);
    gpu::ScopedDevice deviceOwner;
    gpu::Device& device = *deviceOwner;
    out << "# device: " << device.name << "\n# mesh: icosphere, " << sphere.V.rows() << " vertices, 1024x1024, 4x MSAA\n";
    {
        Renderer renderer(device, 1024, 1024, 4);
        renderer.addMesh(sphere);
        const Camera camera = frameMesh(sphere, { 20, 10 }, 1024, 1024);
        renderer.render(camera);
        std::vector<double> ms;
        for (int r = 0; r < options.repeat; ++r) {
            Stopwatch wall;
            renderer.render(camera);
            ms.push_back(wall.milliseconds());
        }
        out << "render_1024_ms " << median(ms) << " ms\n";
    }
}

} // namespace facesketch::app

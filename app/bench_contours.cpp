// Benchmarks of the contour engine (thesis 4.3, 4.4): the one-time curvature pass over a whole
// batch and the per-view candidate cloud, on the GPU and with the single-threaded CPU reference.

#include "bench.h"

#include "contours/candidates.h"
#include "contours/candidates_gpu.h"
#include "contours/curvature.h"
#include "contours/curvature_gpu.h"
#include "core/stopwatch.h"
#include "geometry/mesh_batch.h"
#include "geometry/primitives.h"

#include <cmath>
#include <random>

namespace facesketch::app {

namespace {

// `meshes` distinct face-sized bumpy patches (150 x 150 mm, a dome with ripples) of about
// `vertices` vertices: the cost per vertex of the kernels does not depend on what the surface
// looks like, only on the topology's valence, which a grid shares with a face mesh.
std::vector<Mesh> facePatches(int meshes, int vertices)
{
    const int side = std::max(3, static_cast<int>(std::lround(std::sqrt(double(vertices)))));
    const Mesh grid = makeGrid(side, side, 150.0, 150.0);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Mesh> out;
    for (int m = 0; m < meshes; ++m) {
        Mesh face = grid;
        const double a = u(rng), b = u(rng), c = u(rng);
        for (Eigen::Index v = 0; v < face.V.rows(); ++v) {
            const double x = face.V(v, 0), y = face.V(v, 1);
            face.V(v, 2) = 60 * std::exp(-(x * x + y * y) / (2 * 60.0 * 60.0)) + 6 * a * std::sin(0.08 * x + b) * std::cos(0.06 * y + c);
        }
        out.push_back(face);
    }
    return out;
}

} // namespace

void benchContours(const BenchOptions& options, std::ostream& out)
{
    const std::vector<Mesh> meshes = facePatches(options.meshes, options.vertices);
    const Eigen::Index nv = meshes[0].V.rows();
    const std::string tag = std::to_string(nv) + "v";
    gpu::ScopedDevice deviceOwner;
    gpu::Device& device = *deviceOwner;
    out << "# device: " << device.name << (device.validation ? " (validation on: timings not representative)" : "") << "\n";
    out << "# batch: " << meshes.size() << " meshes x " << nv << " vertices\n";

    ContourParams params;
    params.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    params.featureSize = meanEdgeLength(meshes[0]);
    const Camera camera = frameMesh(meshes[0], {30, 10}, 1920, 1080, Projection::Perspective);
    ContourParams stroke = params; // a stroke's bounding box (200 x 150 px) plus margin
    stroke.rect[0] = 860;
    stroke.rect[1] = 400;
    stroke.rect[2] = 1060;
    stroke.rect[3] = 550;
    {
        GpuCurvature curvature(device, meshes[0].F, nv);
        Stopwatch upload;
        const std::vector<float> positions = meshMajorPositions(meshes);
        curvature.setPositions(positions);
        out << "curvature_upload_" << tag << "_ms " << upload.milliseconds() << " ms\n";
        curvature.run(); // warm-up
        std::vector<double> ms;
        for (int r = 0; r < options.repeat; ++r)
            ms.push_back(curvature.run());
        out << "curvature_gpu_" << tag << "_ms " << median(ms) << " ms\n";

        GpuCandidates cloud(device, curvature, {});
        size_t count = 0, strokeCount = 0;
        std::vector<double> full, culled, fullWall;
        for (int r = 0; r < options.repeat + 1; ++r) {
            double gpuMs = 0;
            Stopwatch wall;
            count = cloud.build(camera, params, &gpuMs).size();
            if (r > 0) { // the first run sizes the output buffer
                full.push_back(gpuMs);
                fullWall.push_back(wall.milliseconds());
            }
            strokeCount = cloud.build(camera, stroke, &gpuMs).size();
            if (r > 0)
                culled.push_back(gpuMs);
        }
        out << "candidates_gpu_" << tag << "_ms " << median(full) << " ms\n";
        out << "candidates_gpu_with_readback_" << tag << "_ms " << median(fullWall) << " ms\n";
        out << "candidates_gpu_stroke_box_" << tag << "_ms " << median(culled) << " ms\n";
        out << "candidates_count_" << tag << " " << count << " points\n";
        out << "candidates_stroke_box_count_" << tag << " " << strokeCount << " points\n";
    }

    // Single-threaded CPU reference on a subset, scaled to the whole batch (it is linear in meshes).
    const int cpuMeshes = std::min<int>(static_cast<int>(meshes.size()), 10);
    Stopwatch cpuCurvature;
    std::vector<Curvature> curv;
    for (int m = 0; m < cpuMeshes; ++m)
        curv.push_back(estimateCurvature(meshes[m]));
    const double scale = double(meshes.size()) / cpuMeshes;
    out << "curvature_cpu_1thread_" << tag << "_ms " << cpuCurvature.milliseconds() * scale << " ms\n";
    const std::vector<Mesh> subset(meshes.begin(), meshes.begin() + cpuMeshes);
    Stopwatch cpuCandidates;
    contourCandidates(subset, curv, {}, camera, params);
    out << "candidates_cpu_1thread_" << tag << "_ms " << cpuCandidates.milliseconds() * scale << " ms\n";
}

} // namespace facesketch::app

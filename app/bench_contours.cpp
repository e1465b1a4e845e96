// Benchmarks of the contour engine (thesis 4.3, 4.4): the one-time curvature pass over a whole
// batch and the per-view candidate cloud, on the GPU and with the single-threaded CPU reference.

#include "bench.h"

#include "contours/candidates.h"
#include "contours/candidates_gpu.h"
#include "contours/curvature.h"
#include "contours/curvature_gpu.h"
#include "core/stopwatch.h"
#include "geometry/mesh_batch.h"
#include "dataset/face_model.h"
#include "dataset/face_params.h"
#include "evaluation/contour_eval.h"
#include "geometry/camera.h"
#include "model/head_model.h"

#include <algorithm>


namespace facesketch::app {

namespace {

// The faces a user's cloud is built from: `meshes` synthetic identities (facesketch synth,
// seed 1) at the resolution nearest `vertices` (low ~900, high ~6,000, ultra ~25,000), skin
// only, with the dataset's labelled and excluded vertices, as `eval contours` uses them.
struct BenchFaces {
    std::vector<Mesh> meshes;
    std::vector<std::uint32_t> flags;
};

BenchFaces syntheticFaces(int meshes, int vertices)
{
    const dataset::Resolution resolution = vertices < 2500    ? dataset::Resolution::Low
                                           : vertices < 12000 ? dataset::Resolution::High
                                                              : dataset::Resolution::Ultra;
    const dataset::FaceTopology topology = dataset::buildFaceTopology(resolution);
    const dataset::Manifest& m = topology.labels;
    const dataset::Component& skin = *m.component("skin");
    const Triangles F = model::skinTriangles(m);
    BenchFaces out;
    out.flags = evaluation::skinContourFlags(m);
    for (int i = 0; i < meshes; ++i) {
        const Vertices V = dataset::synthesizeFace(topology, dataset::sampleFaceParams(1, i));
        out.meshes.push_back(Mesh{V.middleRows(skin.begin, skin.size()), F});
    }
    return out;
}

} // namespace

void benchContours(const BenchOptions& options, std::ostream& out)
{
    const BenchFaces faces = syntheticFaces(options.meshes, options.vertices);
    const std::vector<Mesh>& meshes = faces.meshes;
    const Eigen::Index nv = meshes[0].V.rows();
    const std::string tag = std::to_string(nv) + "v";
    gpu::ScopedDevice deviceOwner;
    gpu::Device& device = *deviceOwner;
    out << "# device: " << device.name << (device.validation ? " (validation on: timings not representative)" : "") << "\n";
    out << "# batch: " << meshes.size() << " meshes x " << nv << " vertices\n";

    ContourParams params;
    params.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    params.featureSize = meanEdgeLength(meshes[0]);
    // A three-quarter view (the thesis' sketching view) of the whole face at 1920 x 1080.
    const Camera camera = frameMesh(meshes[0], parseView("34"), 1920, 1080, Projection::Perspective);
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
        std::vector<double> ms, wallMs;
        for (int r = 0; r < options.repeat; ++r) {
            Stopwatch wall;
            ms.push_back(curvature.run());
            wallMs.push_back(wall.milliseconds());
        }
        out << "curvature_gpu_" << tag << "_ms " << median(ms) << " ms\n";
        // Also the shapes' readback and the host's normal cones and sign locks (setViewBounds).
        out << "curvature_gpu_with_view_bounds_" << tag << "_ms " << median(wallMs) << " ms\n";

        GpuCandidates cloud(device, curvature, faces.flags);
        size_t count = 0, strokeCount = 0;
        std::vector<double> full, culled, fullWall, culledWall;
        for (int r = 0; r < options.repeat + 1; ++r) {
            double gpuMs = 0;
            Stopwatch wall;
            count = cloud.build(camera, params, &gpuMs).size();
            if (r > 0) { // the first run sizes the output buffer
                full.push_back(gpuMs);
                fullWall.push_back(wall.milliseconds());
            }
            Stopwatch strokeWall;
            strokeCount = cloud.build(camera, stroke, &gpuMs).size();
            if (r > 0) {
                culled.push_back(gpuMs);
                culledWall.push_back(strokeWall.milliseconds());
            }
        }
        out << "candidates_gpu_" << tag << "_ms " << median(full) << " ms\n";
        // This machine's speed swings by up to 2x between consecutive runs: the fastest run
        // shows what the kernels cost when nothing else competes for the cores.
        out << "candidates_gpu_fastest_" << tag << "_ms " << *std::min_element(full.begin(), full.end()) << " ms\n";
        out << "candidates_gpu_with_readback_" << tag << "_ms " << median(fullWall) << " ms\n";
        out << "candidates_gpu_stroke_box_" << tag << "_ms " << median(culled) << " ms\n";
        out << "candidates_gpu_stroke_box_with_listing_and_readback_" << tag << "_ms " << median(culledWall) << " ms\n";
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
    contourCandidates(subset, curv, faces.flags, camera, params);
    out << "candidates_cpu_1thread_" << tag << "_ms " << cpuCandidates.milliseconds() * scale << " ms\n";
}

} // namespace facesketch::app

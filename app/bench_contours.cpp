// Benchmarks of the contour engine (thesis 4.3, 4.4): the one-time curvature pass over a whole
// batch and the per-view candidate cloud, on the GPU and with the single-threaded CPU reference.

#include "bench.h"

#include "contours/candidates.h"
#include "contours/candidates_gpu.h"
#include "contours/culling_gpu.h"
#include "contours/curvature.h"
#include "contours/curvature_gpu.h"
#include "core/stopwatch.h"
#include "dataset/synth/face_generator.h"
#include "dataset/synth/face_params.h"
#include "evaluation/contour_eval.h"
#include "geometry/camera.h"
#include "geometry/mesh_batch.h"
#include "gpu/compute.h"
#include "model/head_model.h"

#include <algorithm>
#include <cmath>

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
    const dataset::Resolution resolution = vertices < 2500 ? dataset::Resolution::Low
        : vertices < 12000                                 ? dataset::Resolution::High
                                                           : dataset::Resolution::Ultra;
    const dataset::FaceTopology topology = dataset::buildFaceTopology(resolution);
    const dataset::Manifest& m = topology.labels;
    const dataset::Component& skin = *m.component("skin");
    const Triangles F = model::skinTriangles(m);
    BenchFaces out;
    out.flags = evaluation::skinContourFlags(m);
    for (int i = 0; i < meshes; ++i) {
        const Vertices V = dataset::synthesizeFace(topology, dataset::sampleFaceParams(1, i));
        out.meshes.push_back(Mesh { V.middleRows(skin.begin, skin.size()), F });
    }
    return out;
}

// A variant of the cloud's kernels (--pass1, --pass2) against the built-in ones: the builds
// alternate in one process, in ABBA order, so that this machine's swings (up to 2x between
// runs, from the hypervisor's steal time) fall on both alike. Prints both medians and fastest
// runs, and whether the variant's cloud equals the built-in one.
void compareKernels(const BenchOptions& options, gpu::Device& device, GpuCurvature& curvature, const std::vector<std::uint32_t>& flags,
    const Camera& camera, const ContourParams& params, const std::string& tag, std::ostream& out)
{
    ContourKernels kernels = builtInContourKernels();
    std::vector<std::uint32_t> pass1, pass2;
    if (!options.pass1.empty()) {
        pass1 = gpu::readSpirvFile(options.pass1);
        kernels.radial = { pass1.data(), pass1.size() * sizeof(std::uint32_t) };
    }
    if (!options.pass2.empty()) {
        pass2 = gpu::readSpirvFile(options.pass2);
        kernels.contours = { pass2.data(), pass2.size() * sizeof(std::uint32_t) };
    }
    GpuCandidates builtIn(device, curvature, flags), variant(device, curvature, flags, kernels);
    std::vector<double> builtInMs, variantMs;
    std::vector<Candidate> builtInCloud, variantCloud;
    for (int r = 0; r < options.repeat + 1; ++r) { // the first round sizes the output buffers
        for (int k = 0; k < 2; ++k) {
            const bool variantNow = (k == 1) == (r % 2 == 0);
            double ms = 0;
            std::vector<Candidate> cloud = (variantNow ? variant : builtIn).build(camera, params, &ms);
            if (r > 0)
                (variantNow ? variantMs : builtInMs).push_back(ms);
            (variantNow ? variantCloud : builtInCloud) = std::move(cloud);
        }
    }
    out << "# variant: pass 1 " << (options.pass1.empty() ? "built-in" : options.pass1) << ", pass 2 "
        << (options.pass2.empty() ? "built-in" : options.pass2) << "\n";
    out << "candidates_gpu_ab_builtin_" << tag << "_ms " << median(builtInMs) << " ms\n";
    out << "candidates_gpu_ab_variant_" << tag << "_ms " << median(variantMs) << " ms\n";
    out << "candidates_gpu_ab_builtin_fastest_" << tag << "_ms " << *std::min_element(builtInMs.begin(), builtInMs.end()) << " ms\n";
    out << "candidates_gpu_ab_variant_fastest_" << tag << "_ms " << *std::min_element(variantMs.begin(), variantMs.end()) << " ms\n";
    out << "candidates_ab_variant_count_" << tag << " " << variantCloud.size() << " points\n";
    const auto same = [](const Candidate& a, const Candidate& b) { return a.mesh == b.mesh && a.vertex == b.vertex && a.types == b.types; };
    const bool identical = std::equal(builtInCloud.begin(), builtInCloud.end(), variantCloud.begin(), variantCloud.end(), same);
    out << "# the variant's cloud " << (identical ? "is identical to" : "DIFFERS from") << " the built-in one (" << builtInCloud.size()
        << " points)\n";
    if (identical) { // same points: how far apart the variant puts them
        double world = 0, screen = 0;
        for (size_t i = 0; i < builtInCloud.size(); ++i) {
            const Candidate &a = builtInCloud[i], &b = variantCloud[i];
            for (int k = 0; k < 3; ++k)
                world = std::max(world, double(std::abs(a.world[k] - b.world[k])));
            for (int k = 0; k < 2; ++k)
                screen = std::max(screen, double(std::abs(a.screen[k] - b.screen[k])));
        }
        out << "# largest difference of a point: " << world << " mm in the world, " << screen << " px on the screen\n";
    }
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
        GpuCulling culling(device, curvature);
        std::vector<double> ms, wallMs;
        for (int r = 0; r < options.repeat; ++r) {
            Stopwatch wall;
            ms.push_back(curvature.run());
            culling.update(curvature);
            wallMs.push_back(wall.milliseconds());
        }
        out << "curvature_gpu_" << tag << "_ms " << median(ms) << " ms\n";
        // Also the shapes' readback and the host's normal cones and sign locks (GpuCulling::update).
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
        // rtsc's filter (the test at the crossing reads both ends' shapes in pass 2).
        ContourParams rtsc = params, rtscStroke = stroke;
        rtsc.suggestiveFilter = rtscStroke.suggestiveFilter = SuggestiveFilter::RtscCrossing;
        std::vector<double> rtscFull, rtscCulled;
        size_t rtscCount = 0;
        for (int r = 0; r < options.repeat + 1; ++r) {
            double gpuMs = 0;
            rtscCount = cloud.build(camera, rtsc, &gpuMs).size();
            if (r > 0)
                rtscFull.push_back(gpuMs);
            cloud.build(camera, rtscStroke, &gpuMs);
            if (r > 0)
                rtscCulled.push_back(gpuMs);
        }
        out << "candidates_gpu_rtsc_" << tag << "_ms " << median(rtscFull) << " ms\n";
        out << "candidates_gpu_rtsc_stroke_box_" << tag << "_ms " << median(rtscCulled) << " ms\n";
        out << "candidates_count_rtsc_" << tag << " " << rtscCount << " points\n";
        out << "candidates_count_" << tag << " " << count << " points\n";
        out << "candidates_stroke_box_count_" << tag << " " << strokeCount << " points\n";
        if (!options.pass1.empty() || !options.pass2.empty())
            compareKernels(options, device, curvature, faces.flags, camera, params, tag, out);
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

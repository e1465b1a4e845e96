#include "contours/candidates_gpu.h"
#include "contours/candidates.h"
#include "contours/curvature_gpu.h"
#include "core/random.h"
#include "geometry/mesh_batch.h"
#include "geometry/primitives.h"
#include "test_common.h"

#include <algorithm>
#include <cmath>
#include <set>

using namespace facesketch;

namespace {

struct Batch {
    std::vector<Mesh> meshes;
    std::vector<float> positions;
};

// Bumpy tori: silhouettes from every side and suggestive contours on the inner ring; the minor
// radius grows by `radiusStep` from one to the next.
Batch bumpyTori(int count, int rings = 96, int sides = 48, double radiusStep = 1.0)
{
    Batch b;
    Random random(5);
    for (int m = 0; m < count; ++m) {
        Mesh t = makeTorus(30.0, 9.0 + radiusStep * m, rings, sides);
        const double a = random.uniform(0, 2 * M_PI), c = random.uniform(0, 2 * M_PI);
        for (Eigen::Index v = 0; v < t.V.rows(); ++v)
            t.V(v, 2) *= 1.0 + 0.2 * std::sin(0.15 * t.V(v, 0) + a) * std::cos(0.1 * t.V(v, 1) + c);
        b.meshes.push_back(t);
    }
    b.positions = meshMajorPositions(b.meshes);
    return b;
}

// The CPU reference on the GPU's own packed curvature (decoded to double), so the comparison
// checks the contour kernel itself; tests/contours/curvature_gpu.cpp checks the curvature.
std::vector<Curvature> curvatureFromGpu(const GpuCurvature::Result& r, size_t meshes, Eigen::Index nv)
{
    std::vector<Curvature> out(meshes);
    for (size_t m = 0; m < meshes; ++m) {
        Curvature& c = out[m];
        c.normal.resize(nv, 3);
        c.dir1.resize(nv, 3);
        c.dir2.resize(nv, 3);
        c.k1.resize(nv);
        c.k2.resize(nv);
        c.area.resize(nv);
        c.dcurv.resize(nv, 4);
        for (Eigen::Index v = 0; v < nv; ++v) {
            const float* p = &r.packed[12 * (m * nv + v)];
            const Eigen::Vector3d n(p[0], p[1], p[2]), d1(p[3], p[4], p[5]);
            c.normal.row(v) = n.transpose();
            c.dir1.row(v) = d1.transpose();
            c.dir2.row(v) = n.cross(d1).transpose();
            c.k1[v] = p[6];
            c.k2[v] = p[7];
            c.area[v] = r.curvature[4 * (m * nv + v) + 2];
            for (int k = 0; k < 4; ++k)
                c.dcurv(v, k) = p[8 + k];
        }
    }
    return out;
}

void compareWithReference(const Batch& batch, GpuCurvature& curvature, GpuCandidates& gpu, const std::vector<std::uint32_t>& flags,
    const Camera& camera, const ContourParams& params)
{
    const Eigen::Index nv = batch.meshes[0].V.rows();
    const std::vector<Curvature> curv = curvatureFromGpu(curvature.download(), batch.meshes.size(), nv);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> ties;
    const std::vector<Candidate> cpu = contourCandidates(batch.meshes, curv, flags, camera, params, &ties);
    const std::vector<Candidate> got = gpu.build(camera, params);
    const std::set<std::pair<std::uint32_t, std::uint32_t>> tieSet(ties.begin(), ties.end());

    size_t i = 0, j = 0, matched = 0, tied = 0;
    while (i < cpu.size() || j < got.size()) {
        if (i < cpu.size() && j < got.size() && cpu[i].mesh == got[j].mesh && cpu[i].vertex == got[j].vertex) {
            const bool sameTypes = cpu[i].types == got[j].types;
            if (!sameTypes && !tieSet.count({ cpu[i].mesh, cpu[i].vertex }))
                FAIL("mesh " << cpu[i].mesh << " vertex " << cpu[i].vertex << ": cpu types " << cpu[i].types << " gpu " << got[j].types);
            tied += !sameTypes;
            for (int k = 0; k < 2; ++k)
                REQUIRE(got[j].screen[k] == Approx(cpu[i].screen[k]).margin(1e-2));
            for (int k = 0; k < 3; ++k)
                REQUIRE(got[j].world[k] == cpu[i].world[k]);
            ++matched, ++i, ++j;
            continue;
        }
        // Only one side has it: allowed only at a documented threshold tie.
        const bool cpuFirst = j >= got.size() || (i < cpu.size() && cpu[i] < got[j]);
        const Candidate& only = cpuFirst ? cpu[i] : got[j];
        if (!tieSet.count({ only.mesh, only.vertex }))
            FAIL((cpuFirst ? "only the CPU" : "only the GPU")
                << " has mesh " << only.mesh << " vertex " << only.vertex << " types " << only.types);
        ++tied;
        (cpuFirst ? i : j)++;
    }
    INFO(matched << " candidates matched, " << tied << " differ at documented ties, " << ties.size() << " near ties");
    REQUIRE(matched > 0);
    REQUIRE(tied <= matched / 100 + 2);
}

} // namespace

TEST_CASE("candidates_gpu: the cloud equals the CPU reference, orthographic and perspective, with culling")
{
    const Batch batch = bumpyTori(4);
    const Eigen::Index nv = batch.meshes[0].V.rows();
    GpuCurvature curvature(test::device(), batch.meshes[0].F, nv);
    curvature.setPositions(batch.positions);
    curvature.run();
    std::vector<std::uint32_t> flags(nv, 0);
    for (Eigen::Index v = 0; v < nv; v += 97)
        flags[v] = VertexLabelled;
    for (Eigen::Index v = 50; v < nv; v += 131)
        flags[v] = VertexExcluded;
    GpuCandidates gpu(test::device(), curvature, flags);

    ContourParams params;
    params.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    params.suggestiveThreshold = 0.005;
    params.featureSize = meanEdgeLength(batch.meshes[0]);

    SECTION("orthographic, whole view")
    {
        compareWithReference(batch, curvature, gpu, flags, frameMesh(batch.meshes[0], { 0, 40 }, 640, 480), params);
        // The vertices facing away in all four tori were left out (normal cones), and the
        // cloud still equals the reference.
        REQUIRE(gpu.listedVertices() < nv * 9 / 10);
    }
    SECTION("perspective, culled to a rectangle and a sphere")
    {
        params.rect[0] = 100;
        params.rect[1] = 50;
        params.rect[2] = 500;
        params.rect[3] = 400;
        params.sphere[0] = 20;
        params.sphere[3] = 35;
        compareWithReference(
            batch, curvature, gpu, flags, frameMesh(batch.meshes[0], { 30, 25 }, 640, 480, Projection::Perspective), params);
        REQUIRE(gpu.listedVertices() < nv);
    }
    SECTION("rtsc's filter at the crossing, orthographic and perspective")
    {
        const Camera camera = frameMesh(batch.meshes[0], { 0, 40 }, 640, 480);
        auto suggestive = [&] {
            std::set<std::pair<std::uint32_t, std::uint32_t>> out;
            for (const Candidate& c : gpu.build(camera, params))
                if (c.types & ContourSuggestive)
                    out.insert({ c.mesh, c.vertex });
            return out;
        };
        const auto strength = suggestive();
        params.suggestiveFilter = SuggestiveFilter::RtscCrossing;
        params.rtscThreshold = 0.002;
        const auto rtsc = suggestive();
        // The filters keep different vertices: the GPU follows the one asked for.
        INFO(strength.size() << " suggestive candidates by vertex strength, " << rtsc.size() << " by rtsc's filter");
        REQUIRE(!rtsc.empty());
        REQUIRE(rtsc != strength);
        compareWithReference(batch, curvature, gpu, flags, camera, params);
        compareWithReference(
            batch, curvature, gpu, flags, frameMesh(batch.meshes[0], { 30, 25 }, 640, 480, Projection::Perspective), params);
        params.rtscThreshold = -0.5;
        REQUIRE_THROWS_WITH(gpu.build(frameMesh(batch.meshes[0], { 0, 40 }, 640, 480), params), Catch::Contains("rtsc threshold -0.5"));
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("candidates_gpu: 70 faces, more than one pass-1 invocation per vertex and a partial last one, equal the CPU reference")
{
    // Pass 1 gives each invocation CONTOURS_MESHES_PER_INVOCATION meshes, interleaved across a
    // row's lanes: 70 meshes need two blocks of 64, the second cut short, and a mesh count
    // that is no multiple of 8.
    const Batch batch = bumpyTori(70, 48, 24, 0.2);
    const Eigen::Index nv = batch.meshes[0].V.rows();
    GpuCurvature curvature(test::device(), batch.meshes[0].F, nv);
    curvature.setPositions(batch.positions);
    curvature.run();
    const std::vector<std::uint32_t> flags(nv, 0);
    GpuCandidates gpu(test::device(), curvature, flags);
    ContourParams params;
    params.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    params.suggestiveThreshold = 0.005;
    params.featureSize = meanEdgeLength(batch.meshes[0]);
    const Camera camera = frameMesh(batch.meshes[0], { 20, 35 }, 640, 480, Projection::Perspective);
    compareWithReference(batch, curvature, gpu, flags, camera, params);
    std::set<std::uint32_t> meshes;
    for (const Candidate& c : gpu.build(camera, params))
        meshes.insert(c.mesh);
    REQUIRE(meshes.size() == batch.meshes.size());
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("candidates_gpu: a cloud larger than the first buffer grows it and stays complete")
{
    const Batch batch = bumpyTori(2);
    const Eigen::Index nv = batch.meshes[0].V.rows();
    GpuCurvature curvature(test::device(), batch.meshes[0].F, nv);
    curvature.setPositions(batch.positions);
    curvature.run();
    const std::vector<std::uint32_t> flags(nv, VertexLabelled); // every front-facing vertex
    GpuCandidates gpu(test::device(), curvature, flags);
    ContourParams params;
    params.suggestiveThreshold = 1e30;
    params.featureSize = 1;
    const Camera camera = frameMesh(batch.meshes[0], { 0, 90 }, 256, 256);
    const std::vector<Candidate> got = gpu.build(camera, params);
    const std::vector<Candidate> again = gpu.build(camera, params);
    REQUIRE(got.size() > static_cast<size_t>(2 * nv / 16)); // beyond the initial capacity
    REQUIRE(got.size() == again.size());
    for (size_t i = 1; i < got.size(); ++i)
        REQUIRE(got[i - 1] < got[i]); // sorted, no duplicates
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("candidates_gpu: a stroke's box gives exactly the whole view's candidates inside it")
{
    // The host lists only the vertices some torus may show in the box, and their one-rings, so
    // the kernels visit a fraction of the batch; the candidates must not change. Tiny boxes
    // around suggestive candidates check the one-rings: the neighbour a zero crossing is with
    // lies outside such a box, and its radial curvature must be of this view, not the last.
    const Batch batch = bumpyTori(1); // one torus: point-sized bounding spheres, tight lists
    const Eigen::Index nv = batch.meshes[0].V.rows();
    GpuCurvature curvature(test::device(), batch.meshes[0].F, nv);
    curvature.setPositions(batch.positions);
    curvature.run();
    GpuCandidates gpu(test::device(), curvature, {});
    ContourParams whole;
    whole.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    whole.suggestiveThreshold = 0.005;
    whole.featureSize = meanEdgeLength(batch.meshes[0]);
    for (const Projection kind : { Projection::Perspective, Projection::Orthographic }) {
        const Camera camera = frameMesh(batch.meshes[0], { 20, 35 }, 640, 480, kind);
        const Camera other = frameMesh(batch.meshes[0], { 200, -30 }, 640, 480, kind);
        const std::vector<Candidate> all = gpu.build(camera, whole);
        auto inside = [](const Candidate& c, const ContourParams& box) {
            return c.screen[0] >= box.rect[0] && c.screen[0] <= box.rect[2] && c.screen[1] >= box.rect[1] && c.screen[1] <= box.rect[3];
        };
        auto check = [&](double x, double y, double halfWidth, double halfHeight) {
            ContourParams box = whole;
            box.rect[0] = x - halfWidth;
            box.rect[1] = y - halfHeight;
            box.rect[2] = x + halfWidth;
            box.rect[3] = y + halfHeight;
            std::vector<Candidate> expected;
            for (const Candidate& c : all)
                if (inside(c, box))
                    expected.push_back(c);
            gpu.build(other, whole); // leaves every vertex's radial curvature of another view
            const std::vector<Candidate> got = gpu.build(camera, box);
            INFO(all.size() << " candidates in the whole view, " << expected.size() << " in the box around (" << x << ", " << y << ")");
            REQUIRE(got.size() == expected.size());
            for (size_t i = 0; i < got.size(); ++i) {
                REQUIRE(got[i].mesh == expected[i].mesh);
                REQUIRE(got[i].vertex == expected[i].vertex);
                REQUIRE(got[i].types == expected[i].types);
                REQUIRE(got[i].screen[0] == expected[i].screen[0]);
            }
            return expected.size();
        };
        // The box around the suggestive candidate with the most candidates near it, so that the
        // box holds a real stretch of contour whatever the tori's random phases.
        const Candidate* centre = nullptr;
        size_t most = 0;
        for (const Candidate& c : all) {
            if (!(c.types & ContourSuggestive))
                continue;
            const size_t near = static_cast<size_t>(std::count_if(all.begin(), all.end(), [&](const Candidate& o) {
                return std::abs(o.screen[0] - c.screen[0]) <= 60 && std::abs(o.screen[1] - c.screen[1]) <= 45;
            }));
            if (near > most) {
                most = near;
                centre = &c;
            }
        }
        REQUIRE(centre != nullptr);
        const size_t inBox = check(centre->screen[0], centre->screen[1], 60, 45);
        REQUIRE(inBox > 10);
        REQUIRE(inBox * 5 < all.size());
        int tiny = 0;
        for (const Candidate& c : all)
            if ((c.types & ContourSuggestive) && tiny < 40) {
                REQUIRE(check(c.screen[0], c.screen[1], 0.6, 0.6) >= 1);
                ++tiny;
            }
        REQUIRE(tiny >= 10);
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("candidates_gpu: list, record into the caller's command buffer and collect after its fence give what build gives")
{
    // Every front-facing vertex labelled: the cloud outgrows the first output buffer, so
    // collect() also grows it and runs the view again itself.
    const Batch batch = bumpyTori(2);
    const Eigen::Index nv = batch.meshes[0].V.rows();
    GpuCurvature curvature(test::device(), batch.meshes[0].F, nv);
    curvature.setPositions(batch.positions);
    curvature.run();
    const std::vector<std::uint32_t> flags(nv, VertexLabelled);
    GpuCandidates split(test::device(), curvature, flags), whole(test::device(), curvature, flags);
    ContourParams params;
    params.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    params.suggestiveThreshold = 0.005;
    params.featureSize = meanEdgeLength(batch.meshes[0]);
    const Camera camera = frameMesh(batch.meshes[0], { 30, 25 }, 640, 480, Projection::Perspective);

    REQUIRE_THROWS_WITH(split.collect(), Catch::Contains("no view recorded"));
    gpu::Device& device = test::device();
    for (int round = 0; round < 2; ++round) { // the first grows the output, the second fits
        const std::uint32_t listed = split.list(camera, params);
        REQUIRE(listed == split.listedVertices());
        REQUIRE(listed > 0);
        REQUIRE_THROWS_WITH(split.collect(), Catch::Contains("no view recorded"));
        REQUIRE(split.list(camera, params) == listed); // listing again replaces the listed view
        VkCommandBuffer cmd = gpu::beginOneShot(device);
        split.record(cmd);
        REQUIRE(vkEndCommandBuffer(cmd) == VK_SUCCESS);
        auto fenceInfo = gpu::makeStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        VkFence fence = VK_NULL_HANDLE;
        REQUIRE(vkCreateFence(device.device, &fenceInfo, nullptr, &fence) == VK_SUCCESS);
        auto submit = gpu::makeStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        REQUIRE(vkQueueSubmit(device.queue, 1, &submit, fence) == VK_SUCCESS);
        double ms = -2;
        const std::vector<Candidate> got = split.collect(fence, &ms);
        vkDestroyFence(device.device, fence, nullptr);
        vkFreeCommandBuffers(device.device, device.commandPool, 1, &cmd);
        REQUIRE(ms != -2);
        REQUIRE_THROWS_WITH(split.collect(), Catch::Contains("no view recorded")); // collected once only

        const std::vector<Candidate> expected = whole.build(camera, params);
        REQUIRE(whole.listedVertices() == listed);
        REQUIRE(got.size() > std::max<size_t>(1024, 2 * nv / 16)); // beyond the initial capacity
        REQUIRE(got.size() == expected.size());
        for (size_t i = 0; i < got.size(); ++i) {
            INFO("candidate " << i);
            REQUIRE(got[i].mesh == expected[i].mesh);
            REQUIRE(got[i].vertex == expected[i].vertex);
            REQUIRE(got[i].types == expected[i].types);
            for (int k = 0; k < 3; ++k)
                REQUIRE(got[i].world[k] == expected[i].world[k]);
            for (int k = 0; k < 2; ++k)
                REQUIRE(got[i].screen[k] == expected[i].screen[k]);
            REQUIRE(got[i].depth == expected[i].depth);
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("candidates_gpu: a view nobody may see lists nothing, records nothing and collects no candidates")
{
    const Batch batch = bumpyTori(1);
    const Eigen::Index nv = batch.meshes[0].V.rows();
    GpuCurvature curvature(test::device(), batch.meshes[0].F, nv);
    curvature.setPositions(batch.positions);
    curvature.run();
    GpuCandidates gpu(test::device(), curvature, {});
    REQUIRE_THROWS_WITH(gpu.record(VK_NULL_HANDLE), Catch::Contains("no view listed"));
    ContourParams params;
    params.featureSize = meanEdgeLength(batch.meshes[0]);
    params.sphere[0] = 1000; // a culling sphere far from the torus
    params.sphere[3] = 1;
    const Camera camera = frameMesh(batch.meshes[0], { 0, 0 }, 640, 480);
    REQUIRE(gpu.list(camera, params) == 0);
    double ms = -1;
    REQUIRE(gpu.collect(VK_NULL_HANDLE, &ms).empty()); // nothing to record, nothing to wait for
    REQUIRE(ms == 0);
    REQUIRE(gpu.build(camera, params, &ms).empty());
    REQUIRE(gpu.listedVertices() == 0);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

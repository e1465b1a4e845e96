#include "dataset/synth/synth_dataset.h"

#include "core/error.h"
#include "core/parallel.h"
#include "dataset/dataset.h"
#include "dataset/synth/pose_recipes.h"
#include "io/mesh_io.h"

#include <atomic>
#include <cmath>

namespace facesketch::dataset {

namespace fs = std::filesystem;

namespace {

std::string sampleName(int i)
{
    std::string digits = std::to_string(i);
    return "face_" + std::string(digits.size() < 4 ? 4 - digits.size() : 0, '0') + digits;
}

int posedCount(const SynthOptions& o)
{
    if (!o.poses)
        return 0;
    return o.poseIdentities < 0 ? o.identities : std::min(o.poseIdentities, o.identities);
}

} // namespace

Manifest synthManifest(const FaceTopology& topology, const SynthOptions& options)
{
    Manifest m = topology.labels;
    m.units = "mm";
    m.up = "+y";
    m.forward = "+z";
    const std::vector<Role> roles = splitRoles(options.identities);
    for (int i = 0; i < options.identities; ++i) {
        const std::string name = sampleName(i);
        m.samples.push_back({ name, fs::path("faces") / (name + ".ply"), roles[static_cast<size_t>(i)] });
    }
    for (int i = 0; i < posedCount(options); ++i)
        for (const PoseRecipe& r : poseRecipes()) {
            const std::string name = sampleName(i);
            m.poses.push_back({ name, r.name, fs::path("poses") / name / (r.name + ".ply") });
        }
    return m;
}

void writeSynthDataset(const fs::path& folder, const SynthOptions& options, const std::function<void(int, int)>& progress)
{
    if (options.poseIdentities < -1)
        fail("synth: --pose-identities ", options.poseIdentities, " must be 0 or more");
    const FaceTopology topology = buildFaceTopology(options.resolution);
    const Manifest manifest = synthManifest(topology, options);
    const int posed = posedCount(options);
    const int poseCount = static_cast<int>(poseRecipes().size());
    const int total = options.identities + posed * poseCount;

    writeDataset(folder, manifest, [&](const fs::path& tmp) {
        fs::create_directory(tmp / "faces");
        for (int i = 0; i < posed; ++i)
            fs::create_directories(tmp / "poses" / manifest.samples[static_cast<size_t>(i)].name);

        // Jobs are identities; each writes its own files, so the order of completion does not
        // affect any byte written.
        std::atomic<int> done { 0 };
        parallelFor(
            options.identities, options.threads,
            [&](int i) {
                Mesh mesh;
                mesh.F = topology.labels.topology;
                const FaceParams params = sampleFaceParams(options.seed, i);
                const Sample& s = manifest.samples[static_cast<size_t>(i)];
                mesh.V = synthesizeFace(topology, params);
                writePly(tmp / s.file, mesh);
                ++done;
                if (i < posed)
                    for (int k = 0; k < poseCount; ++k) {
                        const Pose& p = manifest.poses[static_cast<size_t>(i * poseCount + k)];
                        mesh.V = synthesizeFace(topology, params, poseRecipes()[static_cast<size_t>(k)].actions);
                        writePly(tmp / p.file, mesh);
                        ++done;
                    }
            },
            [&](int) {
                if (progress)
                    progress(done.load(), total);
            });
        if (progress)
            progress(done.load(), total);
    });
}

} // namespace facesketch::dataset

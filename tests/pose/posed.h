#pragma once
// A small posed synthetic dataset (low resolution, 12 identities with their 36 poses) written into
// a temporary folder, and a pose model trained on it, shared by the tests of one process (ctest
// runs each test case in its own process, so each pays a few seconds at most).
#include "dataset/dataset.h"
#include "dataset/synth/synth_dataset.h"
#include "pose/minimal_poses.h"
#include "pose/pose_data.h"
#include "pose/pose_model.h"
#include "test_common.h"

#include <cstdlib>
#include <filesystem>

namespace facesketch::test {

/// The source tree's minimal-pose table (ctest sets FACESKETCH_SOURCE_DIR and runs in the source
/// tree; the copy the build stages is found from build/tests, not build/tests/pose).
inline std::filesystem::path minimalPosesFile()
{
    const char* source = std::getenv("FACESKETCH_SOURCE_DIR");
    return std::filesystem::path(source ? source : ".") / "assets" / "minimal-poses.json";
}

/// Whether two mixtures are equal to the last bit (priors, means, loadings, noise).
inline bool sameMixture(const stats::Mppca& a, const stats::Mppca& b)
{
    if (a.size() != b.size() || a.priors != b.priors)
        return false;
    for (Eigen::Index k = 0; k < a.size(); ++k) {
        const auto &p = a.components[static_cast<size_t>(k)], &q = b.components[static_cast<size_t>(k)];
        if (p.mean != q.mean || p.W != q.W || p.sigma2 != q.sigma2)
            return false;
    }
    return true;
}

struct PosedSynth {
    TempDir dir;
    dataset::Dataset dataset;
    pose::PoseSet all;     ///< every posed identity
    pose::PoseSet train;   ///< the `train` ones
    pose::PoseSet contour; ///< the `contour` ones (validation)
    pose::PoseSet test;    ///< the `test` ones
    std::vector<pose::MinimalPose> minimal;
};

inline const PosedSynth& posedSynth()
{
    static PosedSynth t; // filled in place: TempDir must not be copied
    static const bool ready = [](PosedSynth& out) {
        dataset::SynthOptions s;
        s.identities = 14;
        s.resolution = dataset::Resolution::Low;
        s.seed = 5;
        s.poses = true;
        dataset::writeSynthDataset(out.dir / "posed", s);
        out.dataset = dataset::openDataset(out.dir / "posed");
        out.all = pose::loadPoseSet(out.dataset, { dataset::Role::Train, dataset::Role::Contour, dataset::Role::Test });
        out.train = pose::selectRole(out.all, dataset::Role::Train);
        out.contour = pose::selectRole(out.all, dataset::Role::Contour);
        out.test = pose::selectRole(out.all, dataset::Role::Test);
        out.minimal = pose::readMinimalPoses(minimalPosesFile());
        return true;
    }(t);
    (void)ready;
    return t;
}

/// Options small enough for a sanitizer build.
inline pose::PoseModelOptions smallPoseOptions()
{
    pose::PoseModelOptions o;
    o.completion.candidates = { 1, 2, 4 };
    o.completion.latentDims = { 2, 8 };
    o.completion.restarts = 1;
    o.mapping.restarts = 1;
    return o;
}

inline const pose::PoseModel& posedModel()
{
    static const pose::PoseModel model = [] {
        const PosedSynth& p = posedSynth();
        return pose::trainPoseModel(p.train, p.contour, p.minimal, smallPoseOptions());
    }();
    return model;
}

} // namespace facesketch::test

// Tests of pose/pose_data: FDP order, the sketchable subset, and the pose training data of a
// posed synthetic set as displacements from each identity's neutral.
#include "pose/pose_data.h"

#include "core/error.h"
#include "dataset/synth/face_generator.h"
#include "io/mesh_io.h"
#include "posed.h"

#include <algorithm>
#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::pose;

TEST_CASE("pose data: FDP names sort by group then point number")
{
    std::vector<std::string> names { "8.10", "2.10", "2.1", "9.3", "2.2", "bogus", "10.1", "8.9" };
    std::sort(names.begin(), names.end(), fdpLess);
    CHECK(names == std::vector<std::string> { "2.1", "2.2", "2.10", "8.9", "8.10", "9.3", "10.1", "bogus" });
}

TEST_CASE("pose data: 32 of the synthetic set's 46 feature points are sketchable")
{
    const test::PosedSynth& p = test::posedSynth();
    REQUIRE(p.all.fps.size() == 46);
    const auto sketchable = std::count_if(p.all.fps.names.begin(), p.all.fps.names.end(), isSketchable);
    CHECK(sketchable == 32);
    CHECK_FALSE(isSketchable("6.1"));
    CHECK_FALSE(isSketchable("9.10"));
    CHECK_FALSE(isSketchable("2.5"));
    CHECK(isSketchable("2.1"));
    CHECK(isSketchable("2.10"));
    CHECK(isSketchable("8.4"));
    CHECK(std::is_sorted(p.all.fps.names.begin(), p.all.fps.names.end(), fdpLess));
}

TEST_CASE("pose data: poses are displacements from each identity's neutral, FP poses the same at the FP vertices")
{
    const test::PosedSynth& p = test::posedSynth();
    const PoseSet& s = p.all;
    REQUIRE(s.identityCount() == 14);
    REQUIRE(s.poseCount() == 36);
    REQUIRE(s.meshDisplacements.rows() == 14 * 36);
    const int neutral = s.poseIndex("neutral");
    const int anger = s.poseIndex("anger");
    REQUIRE(neutral >= 0);
    REQUIRE(anger >= 0);
    for (Eigen::Index i = 0; i < s.identityCount(); ++i) {
        CHECK(s.meshDisplacements.row(s.row(i, neutral)).cwiseAbs().maxCoeff() == 0.0);
        CHECK(s.fpDisplacements.row(s.row(i, neutral)).cwiseAbs().maxCoeff() == 0.0);
    }
    // Identity 3's anger, read back from its file by hand.
    const std::string name = s.identities[3].name;
    const auto it = std::find_if(p.dataset.manifest.poses.begin(), p.dataset.manifest.poses.end(),
        [&](const dataset::Pose& q) { return q.identity == name && q.name == "anger"; });
    REQUIRE(it != p.dataset.manifest.poses.end());
    const Mesh posed = readMesh(p.dataset.folder / it->file);
    const Eigen::VectorXd expected = asVector(posed.V) - s.neutrals.row(3).transpose();
    CHECK((s.meshDisplacements.row(s.row(3, anger)).transpose() - expected).cwiseAbs().maxCoeff() == 0.0);
    for (Eigen::Index f = 0; f < s.fps.size(); ++f) {
        const int v = s.fps.vertices[static_cast<size_t>(f)];
        CHECK(s.fpDisplacements.row(s.row(3, anger)).segment<3>(3 * f) == s.meshDisplacements.row(s.row(3, anger)).segment<3>(3 * v));
    }
    // Anger lowers the brows (thesis fig. 5.12): 4.1 moves down by millimetres.
    CHECK(s.fpDisplacements(s.row(3, anger), 3 * s.fps.index("4.1") + 1) < -1.0);
}

TEST_CASE("pose data: roles select identities")
{
    const test::PosedSynth& p = test::posedSynth();
    CHECK(p.train.identityCount() + p.contour.identityCount() + p.test.identityCount() == p.all.identityCount());
    REQUIRE(p.test.identityCount() >= 1);
    REQUIRE(p.contour.identityCount() >= 1);
    for (const PosedIdentity& id : p.test.identities)
        CHECK(id.role == dataset::Role::Test);
    const Eigen::Index last = p.all.identityCount() - 1;
    CHECK(p.test.neutrals.row(p.test.identityCount() - 1) == p.all.neutrals.row(last));
}

TEST_CASE("pose data: a dataset without poses, or an identity missing a pose, is refused by name")
{
    const test::PosedSynth& p = test::posedSynth();
    dataset::Dataset d = p.dataset;
    d.manifest.poses.clear();
    REQUIRE_THROWS_WITH(loadPoseSet(d, { dataset::Role::Train }), Catch::Contains("no identity with poses"));

    d = p.dataset;
    const std::string second = d.manifest.samples[1].name;
    d.manifest.poses.erase(std::find_if(d.manifest.poses.begin(), d.manifest.poses.end(),
        [&](const dataset::Pose& q) { return q.identity == second && q.name == "pucker"; }));
    REQUIRE_THROWS_WITH(loadPoseSet(d, { dataset::Role::Train }), Catch::Contains(second) && Catch::Contains("35 poses"));

    // Identities load on several threads; with two bad ones the first in manifest order is named,
    // every time.
    std::vector<std::string> train;
    for (const dataset::Sample& s : p.dataset.manifest.samples)
        if (s.role == dataset::Role::Train)
            train.push_back(s.name);
    REQUIRE(train.size() >= 6);
    d = p.dataset;
    for (const std::string& bad : { train[1], train[5] })
        d.manifest.poses.erase(std::find_if(d.manifest.poses.begin(), d.manifest.poses.end(),
            [&](const dataset::Pose& q) { return q.identity == bad && q.name == "pucker"; }));
    for (int run = 0; run < 5; ++run)
        REQUIRE_THROWS_WITH(loadPoseSet(d, { dataset::Role::Train }), Catch::Contains("'" + train[1] + "' has 35 poses"));

    d = p.dataset;
    d.manifest.mpeg4 = { { "2.1", 0 }, { "2.2", 1 } };
    REQUIRE_THROWS_WITH(loadPoseSet(d, { dataset::Role::Train }), Catch::Contains("at least 4"));
    d = p.dataset;
    d.manifest.units = "cm";
    REQUIRE_THROWS_WITH(loadPoseSet(d, { dataset::Role::Train }), Catch::Contains("mm"));
}

TEST_CASE("pose data: gather takes the FP vertices of a face and refuses a face too small")
{
    FeaturePoints fps { { "2.1", "8.3" }, { 2, 0 } };
    Vertices V(3, 3);
    V << 1, 2, 3, 4, 5, 6, 7, 8, 9;
    const Eigen::VectorXd g = fps.gather(V);
    CHECK(g == (Eigen::VectorXd(6) << 7, 8, 9, 1, 2, 3).finished());
    CHECK(fps.gatherFlat(asVector(V)) == g);
    const Vertices small = V.topRows(2);
    REQUIRE_THROWS_WITH(fps.gather(small), Catch::Contains("2.1"));
}

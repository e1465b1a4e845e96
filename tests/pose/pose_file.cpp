// Tests of pose/pose_file: an exact round trip, and a clear error for each kind of bad file.
#include "pose/pose_file.h"

#include "core/error.h"
#include "posed.h"
#include "test_common.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::pose;

TEST_CASE("pose file: a model reads back exactly and maps the same")
{
    const PoseModel& m = test::posedModel();
    test::TempDir dir;
    savePoseModel(m, dir / "p.model");
    const PoseModel r = loadPoseModel(dir / "p.model");
    CHECK(r.vertexCount == m.vertexCount);
    CHECK(r.topology == m.topology);
    CHECK(r.fps.names == m.fps.names);
    CHECK(r.fps.vertices == m.fps.vertices);
    CHECK(r.poseNames == m.poseNames);
    CHECK(r.meanNeutral == m.meanNeutral);
    CHECK(r.fpTraining == m.fpTraining);
    CHECK(r.fpTrainingPose == m.fpTrainingPose);
    REQUIRE(r.minimal.size() == m.minimal.size());
    CHECK(r.minimal.back().pose == m.minimal.back().pose);
    CHECK(r.minimal.back().fps == m.minimal.back().fps);
    CHECK(test::sameMixture(r.completion.primary, m.completion.primary));
    CHECK(test::sameMixture(r.completion.alternative, m.completion.alternative));
    REQUIRE(r.completion.scores.size() == m.completion.scores.size());
    CHECK(r.completion.scores[1].minimalError == m.completion.scores[1].minimalError);
    CHECK(test::sameMixture(r.mapping.joint, m.mapping.joint));
    CHECK(r.mapping.mesh.W == m.mapping.mesh.W);
    const Eigen::VectorXd fp = m.fpTraining.row(40).transpose();
    CHECK(mapToMesh(r.mapping, fp) == mapToMesh(m.mapping, fp));
    // Saving again gives the same bytes.
    savePoseModel(r, dir / "q.model");
    CHECK(test::readBytes(dir / "p.model") == test::readBytes(dir / "q.model"));
}

TEST_CASE("pose file: bad files are refused naming the path and the fault")
{
    const PoseModel& m = test::posedModel();
    test::TempDir dir;
    savePoseModel(m, dir / "p.model");
    const std::string bytes = test::readBytes(dir / "p.model");

    test::writeText(dir / "face.model", "FSKFACE" + std::string(1, '\0') + bytes.substr(8));
    REQUIRE_THROWS_WITH(loadPoseModel(dir / "face.model"), Catch::Contains("not a FaceSketch pose model"));
    std::string old = bytes;
    old[8] = 9;
    test::writeText(dir / "old.model", old);
    REQUIRE_THROWS_WITH(loadPoseModel(dir / "old.model"), Catch::Contains("version 9") && Catch::Contains("train-poses"));
    test::writeText(dir / "short.model", bytes.substr(0, bytes.size() / 2));
    REQUIRE_THROWS_WITH(loadPoseModel(dir / "short.model"), Catch::Contains("truncated"));
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x10;
    test::writeText(dir / "flipped.model", flipped);
    REQUIRE_THROWS_WITH(loadPoseModel(dir / "flipped.model"), Catch::Contains("checksum mismatch"));
    REQUIRE_THROWS_WITH(loadPoseModel(dir / "missing.model"), Catch::Contains("missing.model"));

    // A writer bug that the checksum cannot see: a feature point outside the mesh.
    PoseModel bad = m;
    bad.fps.vertices[2] = bad.vertexCount + 3;
    savePoseModel(bad, dir / "bad.model");
    REQUIRE_THROWS_WITH(loadPoseModel(dir / "bad.model"), Catch::Contains("inconsistent pose model") && Catch::Contains("outside"));
    // Too few feature points is said as such (names and vertices agree).
    PoseModel few = m;
    few.fps.names.resize(3);
    few.fps.vertices.resize(3);
    savePoseModel(few, dir / "few.model");
    REQUIRE_THROWS_WITH(loadPoseModel(dir / "few.model"), Catch::Contains("3 feature points, fewer than 4"));
}

// Tests of stats/rigid: the Umeyama fit against known transforms, the reflection guard, the
// degenerate cases, a head assembled under an exact similarity, and the model file's head.
#include "stats/rigid.h"

#include "core/error.h"
#include "core/random.h"
#include "stats/model_file.h"
#include "test_common.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>

using namespace facesketch;
using namespace facesketch::stats;

namespace {

Vertices randomPoints(Random& random, int n)
{
    Vertices P(n, 3);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 3; ++j)
            P(i, j) = 20.0 * random.normal();
    return P;
}

Similarity knownSimilarity()
{
    Similarity s;
    s.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
    s.scale = 1.3;
    s.translation = { 4.0, -7.0, 2.5 };
    return s;
}

} // namespace

TEST_CASE("rigid: the fit recovers an exact similarity and an exact rigid motion")
{
    Random random(3);
    const Vertices from = randomPoints(random, 12);
    Similarity truth = knownSimilarity();
    Similarity fit = fitSimilarity(from, truth.apply(from));
    CHECK((fit.rotation - truth.rotation).norm() < 1e-12);
    CHECK(std::abs(fit.scale - truth.scale) < 1e-12);
    CHECK((fit.translation - truth.translation).norm() < 1e-10);

    truth.scale = 1.0;
    fit = fitSimilarity(from, truth.apply(from), false);
    CHECK(fit.scale == 1.0);
    CHECK((fit.apply(from) - truth.apply(from)).norm() < 1e-10);
}

TEST_CASE("rigid: mirrored points give a proper rotation, not a reflection")
{
    Random random(4);
    const Vertices from = randomPoints(random, 10);
    Vertices to = from;
    to.col(0) *= -1.0;
    const Similarity fit = fitSimilarity(from, to);
    CHECK(std::abs(fit.rotation.determinant() - 1.0) < 1e-12);
    CHECK((fit.rotation * fit.rotation.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-12);
}

TEST_CASE("rigid: too few or collinear points give the translation of the centroids")
{
    Vertices from(2, 3), to(2, 3);
    from << 0, 0, 0, 1, 0, 0;
    to << 5, 1, 0, 5, 2, 0;
    Similarity fit = fitSimilarity(from, to);
    CHECK(fit.rotation == Eigen::Matrix3d::Identity());
    CHECK(fit.scale == 1.0);
    CHECK((fit.translation - Eigen::Vector3d(4.5, 1.5, 0)).norm() < 1e-12);

    Vertices line(4, 3), moved(4, 3);
    for (int i = 0; i < 4; ++i) {
        line.row(i) << i, 0, 0;
        moved.row(i) << 0, i, 1;
    }
    fit = fitSimilarity(line, moved);
    CHECK(fit.rotation == Eigen::Matrix3d::Identity());
    CHECK((fit.translation - Eigen::Vector3d(-1.5, 1.5, 1)).norm() < 1e-12);
    REQUIRE_THROWS_WITH(fitSimilarity(line, from), Catch::Contains("4 and 2 points"));
}

TEST_CASE("rigid: a head moved by a similarity carries its parts exactly")
{
    // Skin: 30 random points (head vertices 2..31); part "ball": 6 points (head 32..37) and
    // part "bit": head vertices 0 and 1.
    Random random(5);
    const Vertices skin = randomPoints(random, 30), ball = randomPoints(random, 6), bit = randomPoints(random, 2);
    Vertices head(38, 3);
    head << bit, skin, ball;
    HeadLayout layout;
    layout.vertexCount = 38;
    layout.skinBegin = 2;
    layout.topology.resize(1, 3);
    layout.topology << 0, 2, 32;
    layout.parts.push_back(makeRigidPart("ball", { 32, 33, 34, 35, 36, 37 }, skin, head, 8));
    layout.parts.push_back(makeRigidPart("bit", { 0, 1 }, skin, head, 5));
    REQUIRE(layout.parts[0].anchors.size() == 8);
    validateHeadLayout(layout, 30, "test");

    auto flat = [](const Vertices& V) {
        Eigen::VectorXd out(3 * V.rows());
        for (Eigen::Index v = 0; v < V.rows(); ++v)
            out.segment<3>(3 * v) = V.row(v).transpose();
        return out;
    };
    const Similarity motion = knownSimilarity();
    const Mesh moved = assembleHead(layout, flat(skin), flat(motion.apply(skin)));
    CHECK((moved.V - motion.apply(head)).cwiseAbs().maxCoeff() < 1e-10);
    CHECK(moved.F == layout.topology);

    HeadLayout bad = layout;
    bad.parts.pop_back();
    REQUIRE_THROWS_WITH(validateHeadLayout(bad, 30, "test"), Catch::Contains("head vertex 0 is neither skin nor in a rigid part"));
    bad = layout;
    bad.parts[0].anchors.push_back(30);
    REQUIRE_THROWS_WITH(validateHeadLayout(bad, 30, "test"), Catch::Contains("anchor 30 outside the skin"));
    REQUIRE_THROWS_WITH(assembleHead(HeadLayout {}, flat(skin), flat(skin)), Catch::Contains("skin only"));
}

TEST_CASE("rigid: the model file keeps the head layout, and version 1 files are refused")
{
    // A one-segment, one-component model of a 4-vertex skin; the file format does not care
    // whether it was trained.
    FaceModel model;
    model.triangles.resize(2, 3);
    model.triangles << 0, 1, 2, 0, 2, 3;
    model.meanFace = Eigen::VectorXd::LinSpaced(12, 0.0, 11.0);
    model.segmentation.core = Eigen::VectorXi::Zero(4);
    model.segmentation.vertices = { { 0, 1, 2, 3 } };
    model.segmentation.weights = { Eigen::VectorXd::Ones(4) };
    SegmentModel sm;
    Ppca p;
    p.mean = model.meanFace;
    p.W = Eigen::MatrixXd::Identity(12, 2);
    p.sigma2 = 0.5;
    sm.mixture.priors = Eigen::VectorXd::Ones(1);
    sm.mixture.components = { p };
    sm.cleanUp = p;
    model.segments = { sm };
    Ppca c;
    c.mean = Eigen::VectorXd::Zero(2);
    c.W = Eigen::MatrixXd::Ones(2, 1);
    c.sigma2 = 0.1;
    model.correlation.priors = Eigen::VectorXd::Ones(1);
    model.correlation.components = { c };
    model.head.vertexCount = 6;
    model.head.skinBegin = 0;
    model.head.topology.resize(1, 3);
    model.head.topology << 3, 4, 5;
    RigidPart part;
    part.name = "eye_left";
    part.vertices = { 4, 5 };
    part.mean.resize(2, 3);
    part.mean << 1, 2, 3, 4, 5, 6;
    part.anchors = { 1, 3 };
    part.scale = false;
    model.head.parts = { part };

    test::TempDir dir;
    saveFaceModel(model, dir / "head.model");
    const FaceModel back = loadFaceModel(dir / "head.model");
    REQUIRE(back.head.vertexCount == 6);
    REQUIRE(back.head.topology == model.head.topology);
    REQUIRE(back.head.parts.size() == 1);
    CHECK(back.head.parts[0].name == "eye_left");
    CHECK(back.head.parts[0].vertices == part.vertices);
    CHECK(back.head.parts[0].mean == part.mean);
    CHECK(back.head.parts[0].anchors == part.anchors);
    CHECK(back.head.parts[0].scale == false);

    std::ifstream in(dir / "head.model", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bytes[8] = 1; // the version written before the head layout existed
    std::ofstream(dir / "v1.model", std::ios::binary) << bytes;
    REQUIRE_THROWS_WITH(loadFaceModel(dir / "v1.model"), Catch::Contains("version 1") && Catch::Contains("retrain"));
}

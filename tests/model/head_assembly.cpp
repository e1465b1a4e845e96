// Tests of model/head_assembly: anchors chosen on the mean head, and a head assembled under an
// exact similarity carrying its rigid parts exactly.
#include "model/head_assembly.h"

#include "core/error.h"
#include "core/random.h"
#include "geometry/similarity.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::model;
using stats::HeadLayout;

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

Eigen::VectorXd flat(const Vertices& V)
{
    Eigen::VectorXd out(3 * V.rows());
    for (Eigen::Index v = 0; v < V.rows(); ++v)
        out.segment<3>(3 * v) = V.row(v).transpose();
    return out;
}

} // namespace

TEST_CASE("head_assembly: a part's anchors are the skin vertices nearest its centre")
{
    // Skin: ten points on the x axis at x = 0..9; the part sits at x = 6.2, so its three
    // nearest skin vertices are 5, 6 and 7.
    Vertices skin = Vertices::Zero(10, 3);
    for (int i = 0; i < 10; ++i)
        skin(i, 0) = i;
    Vertices head(12, 3);
    head << skin, 6.0, 1.0, 0.0, 6.4, -1.0, 0.0;
    const stats::RigidPart part = makeRigidPart("ball", { 10, 11 }, skin, head, 3, false);
    CHECK(part.name == "ball");
    CHECK(part.vertices == std::vector<int> { 10, 11 });
    CHECK(part.mean == head.bottomRows(2));
    CHECK(part.anchors == std::vector<int> { 5, 6, 7 });
    CHECK(part.scale == false);
    // More anchors asked than skin vertices: all of them.
    CHECK(makeRigidPart("ball", { 10, 11 }, skin, head, 50).anchors.size() == 10);

    REQUIRE_THROWS_WITH(makeRigidPart("ball", {}, skin, head, 3), Catch::Contains("'ball' has no vertices"));
    REQUIRE_THROWS_WITH(makeRigidPart("ball", { 12 }, skin, head, 3), Catch::Contains("vertex 12 outside [0, 12)"));
    REQUIRE_THROWS_WITH(makeRigidPart("ball", { 10 }, skin, head, 0), Catch::Contains("0 anchors asked"));
}

TEST_CASE("head_assembly: a head moved by a similarity carries its parts exactly")
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
    stats::validateHeadLayout(layout, 30, "test");

    const Similarity motion = knownSimilarity();
    const Mesh moved = assembleHead(layout, flat(skin), flat(motion.apply(skin)));
    CHECK((moved.V - motion.apply(head)).cwiseAbs().maxCoeff() < 1e-10);
    CHECK(moved.F == layout.topology);

    REQUIRE_THROWS_WITH(assembleHead(HeadLayout {}, flat(skin), flat(skin)), Catch::Contains("skin only"));
    REQUIRE_THROWS_WITH(assembleHead(layout, flat(skin), flat(skin.topRows(29))), Catch::Contains("skin of 87 values"));
    HeadLayout bad = layout;
    bad.parts[0].anchors.push_back(30);
    REQUIRE_THROWS_WITH(assembleHead(bad, flat(skin), flat(skin)), Catch::Contains("anchor 30 outside [0, 30)"));
}

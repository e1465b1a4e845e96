// Tests of pose/timeline: the cardinal spline passes through its keyframes, is a straight line
// between two keyframes at tension 0, stands still at keyframes at tension 1, is deterministic,
// and refuses bad keyframes and times; the player rebuilds each frame by the mapping.
#include "pose/timeline.h"

#include "core/error.h"
#include "posed.h"

#include <catch2/catch.hpp>
#include <cstring>

using namespace facesketch;
using namespace facesketch::pose;

namespace {

Eigen::VectorXd vec(std::initializer_list<double> values)
{
    Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
    Eigen::Index i = 0;
    for (double x : values)
        v(i++) = x;
    return v;
}

} // namespace

TEST_CASE("timeline: the spline passes through every keyframe, given in any order")
{
    const std::vector<Keyframe> keys { { 2.0, vec({ 1, 2, 3 }) }, { 0.0, vec({ 0, 0, 0 }) }, { 0.5, vec({ -1, 4, 2 }) },
        { 3.5, vec({ 5, 5, -5 }) } };
    for (double tension : { 0.0, 0.5, 1.0 }) {
        const Timeline t(keys, tension);
        CHECK(t.begin() == 0.0);
        CHECK(t.end() == 3.5);
        for (const Keyframe& k : keys)
            CHECK((t.sample(k.time) - k.fp).cwiseAbs().maxCoeff() < 1e-12);
    }
}

TEST_CASE("timeline: two keyframes at tension 0 give the straight line, at tension 1 an ease in and out")
{
    const Timeline line({ { 1.0, vec({ 0, 10 }) }, { 3.0, vec({ 4, 2 }) } }, 0.0);
    CHECK((line.sample(2.0) - vec({ 2, 6 })).cwiseAbs().maxCoeff() < 1e-12);
    CHECK((line.sample(1.5) - vec({ 1, 8 })).cwiseAbs().maxCoeff() < 1e-12);
    const Timeline ease({ { 1.0, vec({ 0, 10 }) }, { 3.0, vec({ 4, 2 }) } }, 1.0);
    // Zero tangents: h01(1/4) = 5/32 of the way at a quarter of the time; symmetric about the middle.
    CHECK((ease.sample(1.5) - vec({ 4 * 5.0 / 32, 10 - 8 * 5.0 / 32 })).cwiseAbs().maxCoeff() < 1e-12);
    CHECK((ease.sample(2.0) - vec({ 2, 6 })).cwiseAbs().maxCoeff() < 1e-12);
    const double h = 1e-6;
    CHECK(((ease.sample(1.0 + h) - ease.sample(1.0)) / h).cwiseAbs().maxCoeff() < 1e-4);
}

TEST_CASE("timeline: Catmull-Rom tangents at an inner keyframe, and the curve is C1 there")
{
    const Timeline t({ { 0.0, vec({ 0 }) }, { 1.0, vec({ 1 }) }, { 3.0, vec({ 5 }) } }, 0.0);
    // m_1 = (5 - 0) / (3 - 0) on both sides of t = 1.
    const double h = 1e-6;
    const double left = (t.sample(1.0)(0) - t.sample(1.0 - h)(0)) / h;
    const double right = (t.sample(1.0 + h)(0) - t.sample(1.0)(0)) / h;
    CHECK(left == Approx(5.0 / 3.0).epsilon(1e-4));
    CHECK(right == Approx(5.0 / 3.0).epsilon(1e-4));
    // The same time always gives the same bits.
    const Eigen::VectorXd a = t.sample(2.2345), b = t.sample(2.2345);
    CHECK(std::memcmp(a.data(), b.data(), sizeof(double)) == 0);
}

TEST_CASE("timeline: bad keyframes and times are refused with a clear message")
{
    REQUIRE_THROWS_WITH(Timeline({ { 0.0, vec({ 1 }) } }), Catch::Contains("1 keyframe(s)"));
    REQUIRE_THROWS_WITH(Timeline({ { 1.0, vec({ 1 }) }, { 1.0, vec({ 2 }) } }), Catch::Contains("two keyframes at time 1"));
    REQUIRE_THROWS_WITH(Timeline({ { 0.0, vec({ 1 }) }, { 1.0, vec({ 2, 3 }) } }), Catch::Contains("keyframe 1"));
    REQUIRE_THROWS_WITH(Timeline({ { 0.0, vec({ 1 }) }, { std::nan(""), vec({ 2 }) } }), Catch::Contains("keyframe 1 has time"));
    REQUIRE_THROWS_WITH(Timeline({ { 0.0, vec({ std::nan("") }) }, { 1.0, vec({ 2 }) } }), Catch::Contains("not finite"));
    REQUIRE_THROWS_WITH(Timeline({ { 0.0, vec({ 1 }) }, { 1.0, vec({ 2 }) } }, 1.5), Catch::Contains("tension 1.5"));
    const Timeline t({ { 0.0, vec({ 1 }) }, { 1.0, vec({ 2 }) } });
    REQUIRE_THROWS_WITH(t.sample(1.5), Catch::Contains("time 1.5 outside the timeline [0, 1]"));
    REQUIRE_THROWS_WITH(t.sample(-0.1), Catch::Contains("outside"));
    REQUIRE_THROWS_AS(t.sample(std::nan("")), Error);
}

TEST_CASE("timeline: the player rebuilds each frame from the sampled FP pose by the mapping")
{
    const PoseModel& m = test::posedModel();
    const test::PosedSynth& p = test::posedSynth();
    const PoseSet& s = p.test;
    const Timeline t({ { 0.0, s.fpDisplacements.row(s.row(0, s.poseIndex("neutral"))).transpose() },
                         { 1.0, s.fpDisplacements.row(s.row(0, s.poseIndex("anger"))).transpose() },
                         { 2.0, s.fpDisplacements.row(s.row(0, s.poseIndex("smile_open"))).transpose() } },
        0.3);
    Mesh face;
    face.V = asVertices(Eigen::VectorXd(s.neutrals.row(0).transpose()));
    face.F = m.topology;
    TimelinePlayer player(m, t, face);
    for (double time : { 0.0, 0.4, 1.0, 1.7, 2.0 })
        CHECK((player.frame(time) - posedFace(m, face.V, t.sample(time))).cwiseAbs().maxCoeff() == 0.0);
    // At a keyframe the frame is the keyframe's pose mapped: anger lowers the brows.
    const int brow = m.fps.vertices[static_cast<size_t>(m.fps.index("4.1"))];
    CHECK(player.frame(1.0)(brow, 1) < face.V(brow, 1) - 1.0);

    Mesh other = face;
    other.V.conservativeResize(face.V.rows() - 3, 3);
    REQUIRE_THROWS_WITH(TimelinePlayer(m, t, other), Catch::Contains("vertices"));
    const Timeline small({ { 0.0, vec({ 1, 2, 3 }) }, { 1.0, vec({ 2, 3, 4 }) } });
    REQUIRE_THROWS_WITH(TimelinePlayer(m, small, face), Catch::Contains("3 values"));
    REQUIRE_THROWS_AS(player.frame(2.5), Error);
}

// Tests of stats/head_layout: the consistency check names each kind of broken layout.
#include "stats/head_layout.h"

#include "core/error.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::stats;

namespace {

// A head of 8 vertices: part "bit" (0, 1), skin (2..5, four vertices), part "ball" (6, 7).
HeadLayout smallLayout()
{
    HeadLayout layout;
    layout.vertexCount = 8;
    layout.skinBegin = 2;
    layout.topology.resize(2, 3);
    layout.topology << 0, 2, 3, 6, 7, 5;
    auto part = [](const std::string& name, std::vector<int> vertices, std::vector<int> anchors) {
        RigidPart p;
        p.name = name;
        p.vertices = std::move(vertices);
        p.mean = Vertices::Zero(static_cast<Eigen::Index>(p.vertices.size()), 3);
        p.anchors = std::move(anchors);
        return p;
    };
    layout.parts = { part("bit", { 0, 1 }, { 0, 1 }), part("ball", { 6, 7 }, { 2, 3 }) };
    return layout;
}

} // namespace

TEST_CASE("head_layout: a consistent layout passes")
{
    REQUIRE_NOTHROW(validateHeadLayout(smallLayout(), 4, "test"));
}

TEST_CASE("head_layout: each inconsistency is named")
{
    const auto rejects = [](const HeadLayout& layout, Eigen::Index skin, const std::string& expected) {
        REQUIRE_THROWS_WITH(validateHeadLayout(layout, skin, "where"), Catch::StartsWith("where: ") && Catch::Contains(expected));
    };
    rejects(smallLayout(), 7, "head of 8 vertices cannot hold 7 skin vertices from 2");
    rejects(HeadLayout {}, 4, "head of 0 vertices");

    HeadLayout bad = smallLayout();
    bad.parts.pop_back();
    rejects(bad, 4, "head vertex 6 is neither skin nor in a rigid part");
    bad = smallLayout();
    bad.parts[1].anchors.push_back(4);
    rejects(bad, 4, "rigid part 'ball' has anchor 4 outside the skin [0, 4)");
    bad = smallLayout();
    bad.parts[1].vertices[1] = 8;
    rejects(bad, 4, "rigid part 'ball' holds vertex 8 outside [0, 8)");
    bad = smallLayout();
    bad.parts[1].vertices[1] = 5;
    rejects(bad, 4, "rigid part 'ball' holds vertex 5, already in the skin or another part");
    bad = smallLayout();
    bad.parts[0].mean = Vertices::Zero(3, 3);
    rejects(bad, 4, "rigid part 'bit' has 2 vertices, 3 mean positions and 2 anchors");
    bad = smallLayout();
    bad.parts[0].anchors.clear();
    rejects(bad, 4, "0 anchors");
    bad = smallLayout();
    bad.topology(1, 2) = 8;
    rejects(bad, 4, "a head triangle index outside [0, 8)");
}

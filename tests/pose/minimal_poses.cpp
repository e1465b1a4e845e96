// Tests of pose/minimal_poses: the shipped table reads and covers the 35 non-neutral poses with
// sketchable FPs; malformed tables are refused naming the entry.
#include "pose/minimal_poses.h"

#include "core/error.h"
#include "dataset/synth/pose_recipes.h"
#include "pose/pose_data.h"
#include "posed.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::pose;

TEST_CASE("minimal poses: the shipped table names every pose but neutral, with sketchable FPs only")
{
    const std::vector<MinimalPose> table = readMinimalPoses(test::minimalPosesFile());
    CHECK(table.size() == dataset::poseRecipes().size() - 1);
    for (const dataset::PoseRecipe& r : dataset::poseRecipes()) {
        const auto it = std::find_if(table.begin(), table.end(), [&](const MinimalPose& m) { return m.pose == r.name; });
        CHECK((it != table.end()) == (r.name != "neutral"));
    }
    for (const MinimalPose& m : table) {
        CHECK_FALSE(m.fps.empty());
        CHECK(m.fps.size() <= 3);
        for (const std::string& fp : m.fps)
            CHECK(isSketchable(fp));
    }
    // The thesis' own examples: anger from three points of the left brow, an open smile from a lip corner.
    const auto anger = std::find_if(table.begin(), table.end(), [](const MinimalPose& m) { return m.pose == "anger"; });
    REQUIRE(anger != table.end());
    CHECK(anger->fps == std::vector<std::string> { "4.1", "4.3", "4.5" });
}

TEST_CASE("minimal poses: loadMinimalPoses reads the table from the assets folder")
{
    // The override names the source tree's assets folder (the staged copy sits beside build/tests).
    ::setenv("FACESKETCH_ASSETS", test::minimalPosesFile().parent_path().c_str(), 1);
    const std::vector<MinimalPose> table = loadMinimalPoses();
    ::unsetenv("FACESKETCH_ASSETS");
    const std::vector<MinimalPose> direct = readMinimalPoses(test::minimalPosesFile());
    REQUIRE(table.size() == direct.size());
    for (size_t i = 0; i < table.size(); ++i) {
        CHECK(table[i].pose == direct[i].pose);
        CHECK(table[i].fps == direct[i].fps);
    }
}

TEST_CASE("minimal poses: malformed tables are refused naming the entry")
{
    test::TempDir dir;
    auto expect = [&](const std::string& text, const std::string& message) {
        test::writeText(dir / "t.json", text);
        REQUIRE_THROWS_WITH(readMinimalPoses(dir / "t.json"), Catch::Contains(message));
    };
    expect("[1, 2]", "expected {\"poses\"");
    expect("{\"poses\": {\"anger\": []}}", "poses.anger: expected a non-empty list");
    expect("{\"poses\": {\"anger\": [\"4.1\", \"4.1\"]}}", "'4.1' appears twice");
    expect("{\"poses\": {\"anger\": [\"brow\"]}}", "'brow' is not an FDP name");
    expect("{\"poses\": {\"anger\": [41]}}", "41 is not a string");
    expect("{\"poses\": ", "not JSON");
    REQUIRE_THROWS_WITH(readMinimalPoses(dir / "missing.json"), Catch::Contains("missing.json"));
    test::writeText(dir / "ok.json", "{\"poses\": {\"smile_open\": [\"8.4\"], \"anger\": [\"4.1\", \"4.3\"]}}");
    const auto table = readMinimalPoses(dir / "ok.json");
    REQUIRE(table.size() == 2);
    CHECK(table[0].pose == "anger");
    CHECK(table[1].fps == std::vector<std::string> { "8.4" });
}

// Tests of core/assets: the search order, the override, the error naming what was searched,
// and the copy the build puts beside its binaries.
#include "core/assets.h"

#include "core/error.h"
#include "test_common.h"

#include <catch2/catch.hpp>

using namespace facesketch;
namespace fs = std::filesystem;

TEST_CASE("assets: installed folder first, then the folder beside the executable")
{
    const std::vector<fs::path> folders = assetFolders("/opt/fs/bin/facesketch", nullptr);
    REQUIRE(folders.size() == 2);
    CHECK(folders[0] == fs::path("/opt/fs/share/facesketch"));
    CHECK(folders[1] == fs::path("/opt/fs/bin/assets"));
    CHECK(assetFolders("/opt/fs/bin/facesketch", "") == folders);
    // The override is the only folder searched.
    CHECK(assetFolders("/opt/fs/bin/facesketch", "/home/me/recipes") == std::vector<fs::path> { "/home/me/recipes" });
    CHECK(assetFolders("", nullptr).empty());
}

TEST_CASE("assets: the first folder holding the file wins, and a miss names every folder")
{
    test::TempDir dir;
    fs::create_directories(dir / "prefix/bin");
    fs::create_directories(dir / "prefix/share/facesketch");
    fs::create_directories(dir / "prefix/bin/assets");
    test::writeText(dir / "prefix/share/facesketch/a.json", "{}");
    test::writeText(dir / "prefix/bin/assets/a.json", "{}");
    test::writeText(dir / "prefix/bin/assets/b.json", "{}");
    const auto folders = assetFolders(dir / "prefix/bin/facesketch", nullptr);
    CHECK(findAsset("a.json", folders) == dir / "prefix/share/facesketch/a.json");
    CHECK(findAsset("b.json", folders) == dir / "prefix/bin/assets/b.json");
    // A folder of that name is not the asset.
    fs::create_directories(dir / "prefix/share/facesketch/c.json");
    REQUIRE_THROWS_WITH(findAsset("c.json", folders),
        Catch::Contains("cannot find the asset c.json") && Catch::Contains((dir / "prefix/share/facesketch").string())
            && Catch::Contains((dir / "prefix/bin/assets").string()) && Catch::Contains("FACESKETCH_ASSETS"));
    REQUIRE_THROWS_WITH(findAsset("a.json", {}), Catch::Contains("executable's path is unknown"));
}

TEST_CASE("assets: the build copies the assets beside its binaries")
{
    const fs::path exe = executablePath();
    REQUIRE(exe.filename() == "test_core");
    // The real lookup minus the environment: build/tests/test_core finds build/share/facesketch.
    const fs::path recipes = findAsset("ict-poses.json", assetFolders(exe, nullptr));
    CHECK(recipes.parent_path().filename() == "facesketch");
    CHECK(fs::file_size(recipes) > 0);
}

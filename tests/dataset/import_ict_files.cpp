// Tests of dataset/import_ict_files: the ICT-FaceKit importer's JSON readers accept their files
// and refuse malformed and hostile ones (deep nesting, 10 MB strings) naming the file.
#include "dataset/import_ict.h"

#include "core/error.h"
#include "test_common.h"

#include <string>

using namespace facesketch;
using namespace facesketch::dataset;

TEST_CASE("import_ict_files: vertex_indices.json gives the 68 landmarks, and bad lists are named")
{
    test::TempDir dir;
    std::string list;
    for (int i = 0; i < 68; ++i)
        list += (i ? "," : "") + std::to_string(391 * i);
    test::writeText(dir / "vertex_indices.json", "{\"idx_to_landmark_verts\": [" + list + "]}");
    const std::vector<int> landmarks = readIctLandmarkIndices(dir / "vertex_indices.json");
    REQUIRE(landmarks.size() == 68);
    REQUIRE(landmarks[67] == 391 * 67);

    const auto refused = [&](const std::string& text, const std::string& expected) {
        test::writeText(dir / "bad.json", text);
        REQUIRE_THROWS_WITH(readIctLandmarkIndices(dir / "bad.json"), Catch::Contains("bad.json") && Catch::Contains(expected));
    };
    refused("{\"idx_to_landmark_verts\": [1, 2]}", "has 2 entries, expected the 68");
    refused("{\"idx_to_landmark_verts\": [" + list.substr(0, list.rfind(',')) + ",26719]}",
        "idx_to_landmark_verts[67]: '26719' is not a vertex index below 26719");
    refused("{\"idx_to_landmark_verts\": [" + list.substr(0, list.rfind(',')) + ",18446744073709551615]}", "idx_to_landmark_verts[67]");
    refused("[]", "idx_to_landmark_verts: missing or not an array");
    refused("{\"idx_to_landmark_verts\": [", "not valid JSON");
    refused(std::string(100000, '[') + std::string(100000, ']'), "byte 64: arrays and objects nested more than 64 deep");
    refused("{\"" + std::string(10 << 20, 'k') + "\": 1}", "byte 1: a string longer than 65536 bytes");
    REQUIRE_THROWS_WITH(readIctLandmarkIndices(dir / "none.json"), Catch::Contains("none.json: cannot open"));
}

TEST_CASE("import_ict_files: pose recipes refuse hostile JSON naming the file")
{
    test::TempDir dir;
    test::writeText(dir / "r.json", "{\"smile\": {\"mouthSmile_L\": 1, \"mouthSmile_R\": 0.5}}");
    const IctPoseRecipes r = readIctPoseRecipes(dir / "r.json");
    REQUIRE(r.size() == 1);
    REQUIRE(r[0].second.at("mouthSmile_R") == 0.5);
    test::writeText(dir / "deep.json", "{\"smile\": " + std::string(5000, '{'));
    REQUIRE_THROWS_WITH(
        readIctPoseRecipes(dir / "deep.json"), Catch::Contains("deep.json: byte 73: arrays and objects nested more than 64 deep"));
    test::writeText(dir / "long.json", "{\"smile\": {\"" + std::string(10 << 20, 'x') + "\": 1}}");
    REQUIRE_THROWS_WITH(readIctPoseRecipes(dir / "long.json"), Catch::Contains("long.json: byte 11: a string longer than 65536 bytes"));
    test::writeText(dir / "up.json", "{\"../up\": {\"jawOpen\": 1}}");
    REQUIRE_THROWS_WITH(readIctPoseRecipes(dir / "up.json"), Catch::Contains("pose name '../up' is empty or not file-name safe"));
    REQUIRE_THROWS_WITH(readIctPoseRecipes(dir / "none.json"), Catch::Contains("none.json: cannot open the pose recipe file"));
}

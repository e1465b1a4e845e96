// manifest.json: round trip and one failing case per validation rule, each naming its field.
#include "dataset/manifest.h"
#include "core/error.h"
#include "test_common.h"

#include <cfenv>
#include <fstream>
#include <nlohmann/json.hpp>

using namespace facesketch;
using namespace facesketch::dataset;

namespace {

// Two triangles over four vertices; skin 0..3, one pose.
Manifest tiny()
{
    Manifest m;
    m.vertexCount = 6;
    m.topology.resize(2, 3);
    m.topology << 0, 1, 2, 0, 2, 3;
    m.components = { { "skin", 0, 4 }, { "eye_left", 4, 6 } };
    m.landmarks = { { "prn", 1 }, { "ch_l", 2 } };
    m.mpeg4 = { { "9.3", 1 }, { "8.3", 2 } };
    m.contours = { { "lip_upper_outer", { 0, 1, 2 } } };
    m.excluded = { 3 };
    m.samples = { { "a", "faces/a.ply", Role::Train }, { "b", "faces/b.ply", Role::Test } };
    m.poses = { { "a", "smile", "poses/a/smile.ply" } };
    return m;
}

// Writes the tiny manifest with one field of the JSON replaced, and returns readManifest's error.
std::string errorWith(const std::string& pointer, const nlohmann::json& value)
{
    test::TempDir dir;
    writeManifest(dir / "manifest.json", tiny());
    nlohmann::json doc = nlohmann::json::parse(test::readBytes(dir / "manifest.json"));
    if (value.is_discarded()) {
        const nlohmann::json::json_pointer ptr(pointer);
        doc[ptr.parent_pointer()].erase(ptr.back());
    } else
        doc[nlohmann::json::json_pointer(pointer)] = value;
    test::writeText(dir / "manifest.json", doc.dump());
    try {
        readManifest(dir / "manifest.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST_CASE("manifest: write then read gives the same manifest, and the same bytes again")
{
    test::TempDir dir;
    const Manifest m = tiny();
    writeManifest(dir / "manifest.json", m);
    const Manifest r = readManifest(dir / "manifest.json");
    REQUIRE(r.units == "mm");
    REQUIRE(r.up == "+y");
    REQUIRE(r.forward == "+z");
    REQUIRE(r.vertexCount == 6);
    REQUIRE(r.topology == m.topology);
    REQUIRE(r.components.size() == 2);
    REQUIRE(r.component("skin")->end == 4);
    REQUIRE(r.component("eye_left")->begin == 4);
    REQUIRE(r.landmarks == m.landmarks);
    REQUIRE(r.mpeg4 == m.mpeg4);
    REQUIRE(r.contours == m.contours);
    REQUIRE(r.excluded == m.excluded);
    REQUIRE(r.samples.size() == 2);
    REQUIRE(r.samples[1].role == Role::Test);
    REQUIRE(r.samples[1].file == "faces/b.ply");
    REQUIRE(r.poses.size() == 1);
    REQUIRE(r.poses[0].name == "smile");
    writeManifest(dir / "again.json", r);
    REQUIRE(test::readBytes(dir / "again.json") == test::readBytes(dir / "manifest.json"));
    REQUIRE(r.samplesWithRole(Role::Train).size() == 1);
}

TEST_CASE("manifest: every bad field is rejected with its name")
{
    using Catch::Contains;
    const nlohmann::json missing = nlohmann::json::value_t::discarded;
    REQUIRE_THAT(errorWith("/landmarks/prn", 9000), Contains("landmarks.prn: vertex 9000 outside [0, 6)"));
    REQUIRE_THAT(errorWith("/landmarks/prn", "x"), Contains("landmarks.prn: expected an integer"));
    REQUIRE_THAT(errorWith("/mpeg4/9.3", -1), Contains("mpeg4.9.3: vertex -1 outside [0, 6)"));
    REQUIRE_THAT(errorWith("/mpeg4/nose", 1), Contains("mpeg4.nose: not an FDP name"));
    REQUIRE_THAT(errorWith("/units", "inch"), Contains("units: 'inch'"));
    REQUIRE_THAT(errorWith("/up", "up"), Contains("up: 'up'"));
    REQUIRE_THAT(errorWith("/forward", "+y"), Contains("forward: '+y' is parallel to up"));
    REQUIRE_THAT(errorWith("/vertex_count", 0), Contains("vertex_count: 0 must be positive"));
    REQUIRE_THAT(errorWith("/topology/1", nlohmann::json::array({ 0, 2, 7 })), Contains("topology[1]: vertex 7 outside [0, 6)"));
    REQUIRE_THAT(errorWith("/topology/1", nlohmann::json::array({ 0, 2, 2 })), Contains("topology[1]: repeats a vertex"));
    REQUIRE_THAT(errorWith("/topology/0", nlohmann::json::array({ 0, 2 })), Contains("topology[0]: expected 3 vertex indices"));
    REQUIRE_THAT(errorWith("/components/eye_left", nlohmann::json::array({ 3, 6 })),
        Contains("components.eye_left: range [3, 6) overlaps components.skin"));
    REQUIRE_THAT(errorWith("/components/eye_left", nlohmann::json::array({ 4, 9 })),
        Contains("components.eye_left: range [4, 9) is empty or outside"));
    REQUIRE_THAT(errorWith("/components/skin", missing), Contains("components.skin: missing"));
    REQUIRE_THAT(
        errorWith("/contours/lip_upper_outer", nlohmann::json::array({ 1 })), Contains("contours.lip_upper_outer: has 1 vertices"));
    REQUIRE_THAT(errorWith("/contours/lip_upper_outer/2", 6), Contains("contours.lip_upper_outer[2]: vertex 6 outside"));
    REQUIRE_THAT(errorWith("/excluded", nlohmann::json::array({ 3, 3 })), Contains("excluded[1]: vertex 3 listed twice"));
    REQUIRE_THAT(errorWith("/samples/1/role", "validation"), Contains("samples[1].role: role 'validation'"));
    REQUIRE_THAT(errorWith("/samples/1/name", "a"), Contains("samples[1].name: duplicate sample 'a'"));
    REQUIRE_THAT(errorWith("/samples/1/file", "../b.ply"), Contains("samples[1].file: '../b.ply' leaves the dataset folder"));
    REQUIRE_THAT(errorWith("/samples/1/file", "/tmp/b.ply"), Contains("samples[1].file: '/tmp/b.ply' must be relative"));
    REQUIRE_THAT(errorWith("/samples/1/file", "faces/a.ply"), Contains("samples[1].file: 'faces/a.ply' is used twice"));
    REQUIRE_THAT(errorWith("/poses/0/identity", "zed"), Contains("poses[0].identity: 'zed' is not a sample name"));
    REQUIRE_THAT(errorWith("/landmarks", missing), Contains("landmarks: missing"));
    REQUIRE_THAT(errorWith("/samples", nlohmann::json::object()), Contains("samples: expected an array"));
}

TEST_CASE("manifest: unreadable and malformed files name the file")
{
    test::TempDir dir;
    REQUIRE_THROWS_WITH(readManifest(dir / "none.json"), Catch::Contains("none.json: cannot open"));
    test::writeText(dir / "bad.json", "{ \"units\": ");
    REQUIRE_THROWS_WITH(readManifest(dir / "bad.json"), Catch::Contains("bad.json: not valid JSON"));
    Manifest m = tiny();
    m.landmarks["prn"] = 42;
    REQUIRE_THROWS_WITH(writeManifest(dir / "m.json", m), Catch::Contains("landmarks.prn: vertex 42 outside [0, 6)"));
    REQUIRE(!std::filesystem::exists(dir / "m.json"));
}

TEST_CASE("manifest: splitRoles is the thesis' 182/48/20 split")
{
    const auto roles = splitRoles(250);
    REQUIRE(std::count(roles.begin(), roles.end(), Role::Train) == 182);
    REQUIRE(std::count(roles.begin(), roles.end(), Role::Contour) == 48);
    REQUIRE(std::count(roles.begin(), roles.end(), Role::Test) == 20);
    REQUIRE(splitRoles(1).size() == 1);
    REQUIRE(splitRoles(1)[0] == Role::Train);
    REQUIRE_THROWS_WITH(splitRoles(0), Catch::Contains("--identities 0"));
}

TEST_CASE("manifest: the MPEG-4 points that are landmarks take the landmarks' vertices, and a missing one is named")
{
    Manifest m;
    int v = 0;
    for (const char* name : { "gn", "pg", "ps_l", "ps_r", "pi_l", "pi_r", "ex_l", "ex_r", "en_l", "en_r" })
        m.landmarks[name] = 10 * ++v;
    labelMpeg4FromLandmarks(m);
    REQUIRE(m.mpeg4.size() == 10);
    REQUIRE(m.mpeg4.at("2.1") == m.landmarks.at("gn"));
    REQUIRE(m.mpeg4.at("2.10") == m.landmarks.at("pg"));
    REQUIRE(m.mpeg4.at("3.7") == m.landmarks.at("ex_l"));
    REQUIRE(m.mpeg4.at("3.12") == m.landmarks.at("ex_r"));
    REQUIRE(m.mpeg4.at("3.11") == m.landmarks.at("en_l"));
    REQUIRE(m.mpeg4.at("3.8") == m.landmarks.at("en_r"));
    m.landmarks.erase("pi_r");
    REQUIRE_THROWS_WITH(labelMpeg4FromLandmarks(m), Catch::Contains("MPEG-4 point 3.4") && Catch::Contains("'pi_r'"));
}

TEST_CASE("manifest: hostile sizes and paths are refused with a clear message")
{
    using Catch::Contains;
    test::TempDir dir;
    const auto readError = [&](const std::string& text) {
        test::writeText(dir / "manifest.json", text);
        try {
            readManifest(dir / "manifest.json");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    // A million nested arrays: refused by the scan, before the parser builds them (and before a
    // message would dump them recursively).
    REQUIRE_THAT(readError("{\"topology\": [" + std::string(1000000, '[') + std::string(1000001, ']') + "}"),
        Contains("manifest.json: byte 76: arrays and objects nested more than 64 deep"));
    // A 10 MB sample name.
    writeManifest(dir / "good.json", tiny());
    std::string big = test::readBytes(dir / "good.json");
    big.replace(big.find("\"a\""), 3, "\"" + std::string(10 << 20, 'a') + "\"");
    REQUIRE_THAT(readError(big), Contains("a string longer than 65536 bytes"));
    // Counts beyond every limit, also as unsigned 64-bit numbers that would wrap to -1.
    REQUIRE_THAT(errorWith("/vertex_count", 4000000000ll), Contains("vertex_count: 4000000000 is out of range"));
    REQUIRE_THAT(errorWith("/vertex_count", 18446744073709551615ull), Contains("vertex_count: 18446744073709551615 is out of range"));
    REQUIRE_THAT(errorWith("/vertex_count", 100000000), Contains("vertex_count: 100000000 is more than the 67108864 vertices"));
    REQUIRE_THAT(errorWith("/topology/0/1", 4000000000ll), Contains("topology[0]: 4000000000 is out of range"));
    // Sample and pose files that leave the folder.
    REQUIRE_THAT(errorWith("/samples/1/file", "../../somewhere/b.ply"),
        Contains("samples[1].file: '../../somewhere/b.ply' leaves the dataset folder"));
    REQUIRE_THAT(errorWith("/samples/1/file", "faces/../../b.ply"), Contains("leaves the dataset folder"));
    REQUIRE_THAT(
        errorWith("/poses/0/file", "/etc/passwd"), Contains("poses[0].file: '/etc/passwd' must be relative to the dataset folder"));
    REQUIRE_THAT(errorWith("/samples/1/file", ""), Contains("samples[1].file: empty file name"));
}

TEST_CASE("manifest: a number too large for a double is refused as invalid JSON, not an uncaught exception")
{
    // Found by the manifest fuzz target (tests/fuzz/manifest/regress-number-overflowing-a-double.json).
    test::TempDir dir;
    test::writeText(dir / "manifest.json", "{\"vertex_count\": 3.4e888888}");
    // The literal overflows inside strtod; the debug test main traps overflow for our own
    // arithmetic, so lift the trap for this parse only.
    const int traps = fegetexcept();
    fedisableexcept(FE_ALL_EXCEPT);
    std::string message = "no error";
    try {
        readManifest(dir / "manifest.json");
    } catch (const Error& e) {
        message = e.what();
    }
    feclearexcept(FE_ALL_EXCEPT);
    if (traps)
        feenableexcept(traps);
    REQUIRE_THAT(message, Catch::Contains("manifest.json: not valid JSON") && Catch::Contains("number overflow"));
}

TEST_CASE("manifest: millimetresPer scales mm, cm and m and names anything else")
{
    REQUIRE(millimetresPer("mm", "x") == 1.0);
    REQUIRE(millimetresPer("cm", "x") == 10.0);
    REQUIRE(millimetresPer("m", "x") == 1000.0);
    REQUIRE_THROWS_WITH(millimetresPer("inch", "scan.points.json"), "scan.points.json: units 'inch' are not mm, cm or m");
    REQUIRE_THROWS_WITH(millimetresPer("MM", "--units"), Catch::Contains("--units: units 'MM'"));
}

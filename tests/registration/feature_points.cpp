// Tests of registration/feature_points: reading the JSON, the checks with their messages, and
// completing a face mask's points from the template (thesis 3.2.6).
#include "registration/feature_points.h"

#include "core/error.h"
#include "geometry/similarity.h"
#include "registration/surface_query.h"
#include "test_common.h"
#include "test_head.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::registration;

TEST_CASE("readFeaturePoints: reads names and positions")
{
    test::TempDir dir;
    test::writeText(dir / "p.json", R"({"prn": [1, 2.5, -3], "en_l": [4, 5, 6]})");
    const FeaturePoints p = readFeaturePoints(dir / "p.json");
    REQUIRE(p.size() == 2);
    REQUIRE(p.at("prn") == Eigen::Vector3d(1, 2.5, -3));
    REQUIRE(p.at("en_l") == Eigen::Vector3d(4, 5, 6));
}

TEST_CASE("readFeaturePoints: names the file and key of a bad entry")
{
    test::TempDir dir;
    test::writeText(dir / "a.json", R"({"nose": [1, 2, 3]})");
    REQUIRE_THROWS_WITH(readFeaturePoints(dir / "a.json"), Catch::Contains("a.json: nose: not a landmark name"));
    test::writeText(dir / "b.json", R"({"prn": [1, 2]})");
    REQUIRE_THROWS_WITH(readFeaturePoints(dir / "b.json"), Catch::Contains("b.json: prn: expected [x, y, z]"));
    test::writeText(dir / "c.json", R"({"prn": [1, "x", 3]})");
    REQUIRE_THROWS_WITH(readFeaturePoints(dir / "c.json"), Catch::Contains("c.json: prn[1]: not a number"));
    test::writeText(dir / "d.json", R"([1, 2, 3])");
    REQUIRE_THROWS_WITH(readFeaturePoints(dir / "d.json"), Catch::Contains("d.json: expected an object"));
    test::writeText(dir / "e.json", R"({"prn": [1, 2, 3])");
    REQUIRE_THROWS_WITH(readFeaturePoints(dir / "e.json"), Catch::Contains("e.json: not JSON"));
    REQUIRE_THROWS_WITH(readFeaturePoints(dir / "missing.json"), Catch::Contains("missing.json: cannot open"));
}

TEST_CASE("validateFeaturePoints: accepts points on the scan, names the point at fault otherwise")
{
    const Mesh scan = test::makeHead(4);
    const SurfaceQuery surface(scan);
    const FeaturePoints good = test::headPoints();
    REQUIRE_NOTHROW(validateFeaturePoints(good, surface, "scan.ply"));

    FeaturePoints missing = good;
    missing.erase("ch_l");
    REQUIRE_THROWS_WITH(validateFeaturePoints(missing, surface, "scan.ply"), Catch::Contains("scan.ply: feature point 'ch_l' is missing"));

    FeaturePoints twice = good;
    twice["li"] = twice["pg"] + Eigen::Vector3d(0.1, 0, 0);
    REQUIRE_THROWS_WITH(validateFeaturePoints(twice, surface, "scan.ply"), Catch::Contains("'li' and 'pg' are at the same place"));

    FeaturePoints far = good;
    far["prn"] += Eigen::Vector3d(0, 0, 10);
    REQUIRE_THROWS_WITH(validateFeaturePoints(far, surface, "scan.ply"), Catch::Contains("scan.ply: feature point 'prn'"));
    REQUIRE_THROWS_WITH(validateFeaturePoints(far, surface, "scan.ply"), Catch::Contains("from the scan's surface"));

    FeaturePoints nan = good;
    nan["sn"](1) = std::nan("");
    REQUIRE_THROWS_WITH(validateFeaturePoints(nan, surface, "scan.ply"), Catch::Contains("'sn' is not finite"));

    FeaturePoints flat;
    for (const auto& name : requiredFeaturePoints())
        flat[name] = Eigen::Vector3d(static_cast<double>(flat.size()) * 3.0, static_cast<double>(flat.size() % 3) * 5.0, 0.0);
    REQUIRE_THROWS_WITH(validateFeaturePoints(flat, surface, "flat.ply"), Catch::Contains("flat.ply: the feature points lie on one plane"));
    FeaturePoints line;
    for (const auto& name : requiredFeaturePoints())
        line[name] = Eigen::Vector3d(static_cast<double>(line.size()) * 3.0, 0.0, 0.0);
    REQUIRE_THROWS_WITH(validateFeaturePoints(line, surface, "line.ply"), Catch::Contains("line.ply: the feature points lie on one line"));
}

TEST_CASE("completeFeaturePoints: estimates a mask's missing points by the similarity of the others")
{
    const FeaturePoints templ = test::headPoints();
    Similarity s;
    s.rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
    s.scale = 1.08;
    s.translation = { 5, -3, 20 };
    FeaturePoints scan;
    for (const auto& [name, p] : templ)
        if (name != "obs_l" && name != "obs_r")
            scan[name] = s.apply(p);
    scan["g"] = Eigen::Vector3d(0, 50, 70); // not on the template: reported unused
    const CompletedPoints c = completeFeaturePoints(templ, scan, "mask.ply");
    REQUIRE(c.names.size() == templ.size());
    REQUIRE(c.estimated == std::vector<std::string> { "obs_l", "obs_r" });
    REQUIRE(c.unused == std::vector<std::string> { "g" });
    for (std::size_t i = 0; i < c.names.size(); ++i) {
        const Eigen::Vector3d expected = s.apply(templ.at(c.names[i]));
        REQUIRE((c.scanPoints.row(static_cast<Eigen::Index>(i)).transpose() - expected).norm() < 1e-9);
        REQUIRE(c.templatePoints.row(static_cast<Eigen::Index>(i)).transpose() == templ.at(c.names[i]));
    }
    FeaturePoints few = { { "prn", scan["prn"] }, { "sn", scan["sn"] }, { "pg", scan["pg"] } };
    REQUIRE_THROWS_WITH(completeFeaturePoints(templ, few, "mask.ply"), Catch::Contains("mask.ply: only 3 feature points"));
}

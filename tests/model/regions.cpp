// Tests of model/regions: regions hold the vertices near their landmarks, compose, and bad
// names fail clearly.
#include "model/regions.h"

#include "core/error.h"
#include "trained.h"

#include <algorithm>
#include <catch2/catch.hpp>

using namespace facesketch;

TEST_CASE("regions: each region holds its landmarks and only nearby vertices")
{
    const test::TrainedSynth& t = test::trainedSynth();
    const dataset::Manifest& m = t.dataset.manifest;
    const stats::FaceModel& model = t.model;
    auto has = [](const std::vector<int>& r, int v) { return std::binary_search(r.begin(), r.end(), v); };
    for (const std::string& name : model::featureRegionNames()) {
        const std::vector<int> r = model::featureRegion(m, model, name, 8.0);
        INFO(name << ": " << r.size() << " vertices");
        CHECK(std::is_sorted(r.begin(), r.end()));
        CHECK(r.size() < static_cast<size_t>(model.vertexCount()) / 2);
    }
    const std::vector<int> nose = model::featureRegion(m, model, "nose", 8.0);
    CHECK(has(nose, model::skinLandmark(m, "prn")));
    CHECK(!has(nose, model::skinLandmark(m, "pg")));
    for (int v : nose) {
        const Eigen::Vector3d p = model.meanFace.segment<3>(3 * v);
        const Eigen::Vector3d tip = model.meanFace.segment<3>(3 * model::skinLandmark(m, "prn"));
        CHECK((p - tip).norm() < 60.0);
    }
    const std::vector<int> mouth = model::featureRegion(m, model, "mouth", 8.0);
    const std::vector<int> chin = model::featureRegion(m, model, "chin", 8.0);
    std::vector<int> both;
    std::set_union(mouth.begin(), mouth.end(), chin.begin(), chin.end(), std::back_inserter(both));
    CHECK(model::featureRegion(m, model, "mouth_chin", 8.0) == both);
    // A larger radius never loses a vertex.
    const std::vector<int> wide = model::featureRegion(m, model, "mouth", 12.0);
    CHECK(std::includes(wide.begin(), wide.end(), mouth.begin(), mouth.end()));
    CHECK(wide.size() > mouth.size());

    const std::vector<int> first = model::featureRegion(m, model, "segment:1");
    REQUIRE(!first.empty());
    for (int v : first)
        CHECK(model.segmentation.core(v) == 0);
    REQUIRE_THROWS_WITH(model::featureRegion(m, model, "ears"), Catch::Contains("unknown region 'ears'"));
    REQUIRE_THROWS_WITH(model::featureRegion(m, model, "segment:0"), Catch::Contains("segments 1 to"));
    REQUIRE_THROWS_WITH(model::featureRegion(m, model, "segment:x"), Catch::Contains("segments 1 to"));
}

#include "sketch/mapper.h"

#include "core/error.h"
#include "fixture.h"
#include "geometry/graph.h"
#include "test_common.h"

#include <cmath>
#include <iostream>
#include <set>

using namespace facesketch;
using namespace facesketch::sketch;

namespace {

// The screen trace of a vertex path of `face` in a front view of 512 x 512.
Stroke traceOf(const Mesh& face, const std::vector<int>& path, ViewAngles angles = { 0, 0 })
{
    Stroke s;
    s.view = frameMeshView(face, angles, 512, 512);
    const Camera camera = orbitCamera(s.view);
    for (int v : path) {
        const glm::dvec3 p = camera.project(glm::dvec3(face.V(v, 0), face.V(v, 1), face.V(v, 2)));
        s.points.push_back({ p.x, p.y, std::nullopt });
    }
    return s;
}

// Share of the observed vertices within `hops` of the path, and share of the path observed.
std::pair<double, double> overlap(const StrokeReading& r, const std::vector<int>& path, const RingDistances& rings, int hops)
{
    int near = 0;
    std::set<int> covered;
    for (const VertexObservation& o : r.observations) {
        int best = 1000;
        for (int v : path) {
            const int h = rings.hops(o.vertex, static_cast<std::uint32_t>(v));
            if (h >= 0 && h < best)
                best = h;
        }
        near += best <= hops;
        if (best == 0)
            covered.insert(static_cast<int>(o.vertex));
    }
    return { static_cast<double>(near) / std::max<std::size_t>(r.observations.size(), 1),
        static_cast<double>(covered.size()) / path.size() };
}

void checkWellFormed(const StrokeReading& r, Eigen::Index vertexCount)
{
    REQUIRE(r.screenPoints.size() == r.worldPoints.size());
    REQUIRE(r.candidateCounts.size() == r.screenPoints.size());
    REQUIRE(r.chosen.size() == r.screenPoints.size());
    std::set<std::uint32_t> seen;
    int lastPoint = -1;
    for (const VertexObservation& o : r.observations) {
        REQUIRE(o.vertex < vertexCount);
        REQUIRE(seen.insert(o.vertex).second); // at most one per vertex
        REQUIRE(o.strokePoint >= lastPoint);   // in stroke order
        lastPoint = o.strokePoint;
        REQUIRE(o.strokePoint < static_cast<int>(r.screenPoints.size()));
        REQUIRE(r.candidateCounts[static_cast<std::size_t>(o.strokePoint)] > 0);
        REQUIRE(o.position.allFinite());
    }
}

} // namespace

TEST_CASE("mapper: mapper names round-trip and unknown names are refused")
{
    for (MapperKind k : { MapperKind::Nearest, MapperKind::Heuristic, MapperKind::Hmm, MapperKind::Simple })
        CHECK(parseMapper(mapperName(k)) == k);
    REQUIRE_THROWS_WITH(parseMapper("closest"), Catch::Contains("'closest'"));
    MapperParams p;
    p.sigmaC = 0;
    REQUIRE_THROWS_WITH(p.validate(), Catch::Contains("sigmaC = 0"));
}

TEST_CASE("mapper: a stroke traced along the mean face's upper lip maps to the upper lip")
{
    const test::SketchWorld& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    const std::vector<int>& lip = w.contours.at("lip_upper_outer");
    const Stroke stroke = traceOf(w.mean, lip);
    const RingDistances rings(w.model.triangles, w.model.vertexCount(), 4);
    for (MapperKind kind : { MapperKind::Nearest, MapperKind::Hmm, MapperKind::Simple }) {
        const StrokeReading r = reader.read(stroke, w.mean, kind);
        checkWellFormed(r, w.model.vertexCount());
        const auto [nearShare, covered] = overlap(r, lip, rings, 1);
        std::cout << mapperName(kind) << ": " << r.screenPoints.size() << " points, " << r.observations.size() << " vertices, " << nearShare
                  << " within one ring of the lip, " << covered << " of the lip covered, " << reader.lastTiming().candidatesMs << " + "
                  << reader.lastTiming().mappingMs << " ms\n";
        INFO(mapperName(kind));
        CHECK(r.message.empty());
        CHECK(r.observations.size() >= lip.size() / 2);
        CHECK(covered >= 0.5);
        if (kind == MapperKind::Nearest) {
            // The baseline: every point on its nearest candidate, wherever that vertex lies.
            for (std::size_t i = 0; i < r.chosen.size(); ++i)
                if (r.candidateCounts[i] > 0)
                    CHECK(r.chosen[i] >= 0);
        } else {
            CHECK(nearShare >= 0.9);
        }
        // Every observation lies under the stroke: its image is a stroke point.
        const Camera camera = orbitCamera(stroke.view);
        for (const VertexObservation& o : r.observations) {
            const glm::dvec3 s = camera.project(glm::dvec3(o.position.x(), o.position.y(), o.position.z()));
            const Eigen::Vector2d& p = r.screenPoints[static_cast<std::size_t>(o.strokePoint)];
            if (kind != MapperKind::Nearest && kind != MapperKind::Simple) {
                CHECK(s.x == Approx(p.x()).margin(1e-6));
                CHECK(s.y == Approx(p.y()).margin(1e-6));
            }
        }
    }
    REQUIRE_NO_VALIDATION_MESSAGES();
}

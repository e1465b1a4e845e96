// eval strokes on a small trained model: records per (view, mapper), sketching helps, and all
// views together help more than one; bad input is refused.
#include "evaluation/stroke_eval.h"

#include "core/error.h"
#include "evaluation/contour_eval.h"
#include "model/trained.h"

#include <cmath>
#include <optional>
#include <set>

using namespace facesketch;

namespace {

evaluation::StrokeEvalData smallData()
{
    const auto& t = test::trainedSynth();
    const dataset::Component& skin = *t.dataset.manifest.component("skin");
    const Triangles F = model::skinTriangles(t.dataset.manifest);
    evaluation::StrokeEvalData d;
    d.model = &t.model;
    d.flags = evaluation::skinContourFlags(t.dataset.manifest);
    d.contours = sketch::skinContours(t.dataset.manifest.contours, skin.begin, skin.end);
    for (dataset::Role role : { dataset::Role::Train, dataset::Role::Contour }) {
        const Eigen::MatrixXd rows = dataset::loadShapes(t.dataset, role, "skin");
        for (Eigen::Index i = 0; i < rows.rows(); ++i)
            d.candidateFaces.push_back({ dataset::unflatten(rows.row(i)), F });
    }
    for (Eigen::Index i = 0; i < 3; ++i) {
        d.testFaces.push_back({ dataset::unflatten(t.testSkin.row(i)), F });
        d.testNames.push_back("test" + std::to_string(i));
    }
    return d;
}

// The first record of an evaluation with `oracle`.
evaluation::StrokeEvalRecord firstRecord(
    const evaluation::StrokeEvalData& d, evaluation::StrokeEvalOptions o, evaluation::StrokeOracle oracle)
{
    o.oracle = oracle;
    return evaluation::evaluateStrokes(test::device(), d, o).records.at(0);
}

} // namespace

TEST_CASE("stroke_eval: sketching test faces with their own strokes beats the mean face, all views more than one")
{
    const evaluation::StrokeEvalData d = smallData();
    evaluation::StrokeEvalOptions o;
    o.views = { { "front", { 0, 0 } }, { "profile", { 90, 0 } } };
    o.mappers = { sketch::MapperKind::Nearest };
    o.keepFaces = 1;
    const evaluation::StrokeEvalResult r = evaluation::evaluateStrokes(test::device(), d, o);
    REQUIRE(r.records.size() == 3);
    REQUIRE(r.records[0].view == "front");
    REQUIRE(r.records[2].view == "all");
    for (const auto& rec : r.records) {
        INFO(rec.view << ": " << rec.meanMm << " mm, mean face " << rec.meanFaceMm << " mm, ratio " << rec.ratio);
        REQUIRE(rec.mapper == "nearest");
        REQUIRE(rec.faces == 3);
        REQUIRE(rec.noisePx == 1.0);
        REQUIRE(rec.failed == 0);
        REQUIRE(rec.strokes > 3 * 3);
        REQUIRE(rec.ratio == Approx(rec.meanMm / rec.meanFaceMm));
        REQUIRE(rec.ratio < 1.0);
        // Three faces read differently well: an interval of some width round the ratio.
        REQUIRE(rec.ratioInterval.low < rec.ratio);
        REQUIRE(rec.ratio < rec.ratioInterval.high);
        REQUIRE(!rec.versusNearest); // nearest is not compared with itself
    }
    REQUIRE(r.records[2].ratio < std::min(r.records[0].ratio, r.records[1].ratio));
    REQUIRE(r.records[2].strokes == r.records[0].strokes + r.records[1].strokes);
    REQUIRE(r.kept.size() == 3); // face 0 in front, profile and all
    REQUIRE(r.kept[0].vertexError.mean() == Approx(r.kept[0].meanMm));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("stroke_eval: every other mapper is paired with nearest on the same faces")
{
    const evaluation::StrokeEvalData d = smallData();
    evaluation::StrokeEvalOptions o;
    o.views = { { "front", { 0, 0 } } };
    o.mappers = { sketch::MapperKind::Hmm, sketch::MapperKind::Nearest };
    o.keepFaces = 3;
    const evaluation::StrokeEvalResult r = evaluation::evaluateStrokes(test::device(), d, o);
    const auto record = [&](const std::string& mapper) {
        for (const auto& rec : r.records)
            if (rec.view == "front" && rec.mapper == mapper)
                return rec;
        FAIL("no front record of " << mapper);
        return evaluation::StrokeEvalRecord {};
    };
    const evaluation::StrokeEvalRecord hmm = record("hmm"), nearest = record("nearest");
    REQUIRE(!nearest.versusNearest);
    REQUIRE(hmm.versusNearest);
    const evaluation::PairedDifference& p = *hmm.versusNearest;
    INFO("hmm " << hmm.ratio << ", nearest " << nearest.ratio << ", difference " << p.difference << " (" << p.interval.low << " to "
                << p.interval.high << "), better on " << p.betterFaces);
    REQUIRE(p.baseline == "nearest");
    REQUIRE(p.difference == Approx(hmm.ratio - nearest.ratio).margin(1e-12));
    REQUIRE(p.interval.low <= p.difference);
    REQUIRE(p.difference <= p.interval.high);
    // The faces rebuilt better, counted again from the kept faces' own errors.
    int better = 0;
    for (const auto& h : r.kept)
        if (h.view == "front" && h.mapper == "hmm")
            for (const auto& n : r.kept)
                if (n.view == "front" && n.mapper == "nearest" && n.face == h.face)
                    better += h.meanMm < n.meanMm;
    REQUIRE(p.betterFaces == better);
    // Without nearest among the mappers there is nothing to pair with.
    o.mappers = { sketch::MapperKind::Hmm };
    o.keepFaces = 0;
    REQUIRE(!evaluation::evaluateStrokes(test::device(), d, o).records.at(0).versusNearest);
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("stroke_eval: every stroke's reading is kept on request, and adds up to the records")
{
    const evaluation::StrokeEvalData d = smallData();
    evaluation::StrokeEvalOptions o;
    o.views = { { "front", { 0, 0 } }, { "profile", { 90, 0 } } };
    o.mappers = { sketch::MapperKind::Nearest, sketch::MapperKind::Hmm };
    evaluation::StrokeEvalOptions plain; // off by default (one view and mapper: the readings are not the point)
    plain.views = { o.views.front() };
    plain.mappers = { sketch::MapperKind::Nearest };
    REQUIRE(evaluation::evaluateStrokes(test::device(), d, plain).strokes.empty());
    o.keepStrokes = true;
    const evaluation::StrokeEvalResult r = evaluation::evaluateStrokes(test::device(), d, o);
    REQUIRE(r.records.size() == 6);
    for (const auto& rec : r.records) {
        int drawn = 0, read = 0, withAcross = 0, misread = 0;
        std::set<std::string> faces;
        for (const auto& s : r.strokes) {
            if (s.view != rec.view || s.mapper != rec.mapper)
                continue;
            ++drawn;
            faces.insert(s.face);
            REQUIRE(!s.feature.empty());
            REQUIRE(s.points > 0);
            if (s.outcome != evaluation::StrokeEvalStroke::Outcome::Read) {
                REQUIRE(s.observations == 0);
                REQUIRE(s.readAs.empty());
                continue;
            }
            ++read;
            REQUIRE(s.observations > 0);
            REQUIRE(std::isfinite(s.planeMm));
            REQUIRE((s.readAs == "unlabelled" || d.contours.count(s.readAs) == 1));
            if (s.acrossMm) {
                ++withAcross;
                misread += s.misread;
                REQUIRE(s.misread == (*s.acrossMm > evaluation::kMisreadMm));
            }
        }
        INFO(rec.view << " " << rec.mapper << ": " << drawn << " strokes kept, " << read << " read, " << misread << " misread");
        REQUIRE(drawn == rec.strokes);
        REQUIRE(read == rec.strokes - rec.unread - rec.failed);
        REQUIRE(faces.size() == 3);
        REQUIRE(withAcross > 0);
        REQUIRE(static_cast<double>(misread) / withAcross == Approx(rec.misread).margin(1e-12));
    }
    // The strokes of view "all" are the single views' in turn, each in its own order.
    std::vector<std::string> single, all;
    for (const auto& s : r.strokes)
        if (s.face == "test0" && s.mapper == "hmm")
            (s.view == "all" ? all : single).push_back(s.feature);
    REQUIRE(all == single);

    // Per feature: every kept stroke counted once, in the evaluation's order.
    const std::vector<evaluation::FeatureReadings> rows = evaluation::readingsByFeature(r.strokes);
    int total = 0;
    for (const auto& row : rows) {
        total += row.strokes;
        REQUIRE(row.read <= row.strokes);
        REQUIRE(row.misread <= row.read);
    }
    REQUIRE(total == static_cast<int>(r.strokes.size()));
    REQUIRE(rows.front().view == "front");
    REQUIRE(rows.front().mapper == "nearest");
    REQUIRE(rows.back().view == "all");
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("stroke_eval: readings by feature count strokes, reads and misreads, and average only the read strokes' errors")
{
    using Outcome = evaluation::StrokeEvalStroke::Outcome;
    const auto stroke = [](std::string view, std::string feature, Outcome outcome, std::optional<double> across) {
        evaluation::StrokeEvalStroke s;
        s.view = std::move(view);
        s.feature = std::move(feature);
        s.mapper = "hmm";
        s.outcome = outcome;
        s.acrossMm = across;
        s.misread = across && *across > evaluation::kMisreadMm;
        s.readAs = outcome == Outcome::Read ? "brow" : "";
        return s;
    };
    const std::vector<evaluation::StrokeEvalStroke> strokes
        = { stroke("profile", "eye_slit", Outcome::Read, 2.0), stroke("front", "lip_upper", Outcome::Read, 0.5),
              stroke("profile", "eye_slit", Outcome::Read, 1.0), stroke("profile", "eye_slit", Outcome::Unread, std::nullopt),
              stroke("profile", "eye_slit", Outcome::Read, std::nullopt), stroke("profile", "silhouette", Outcome::Failed, std::nullopt) };
    const std::vector<evaluation::FeatureReadings> rows = evaluation::readingsByFeature(strokes);
    REQUIRE(rows.size() == 3);
    // Views, then features, in the order they first appear.
    REQUIRE(rows[0].view == "profile");
    REQUIRE(rows[0].feature == "eye_slit");
    REQUIRE(rows[0].strokes == 4);
    REQUIRE(rows[0].read == 3);
    REQUIRE(rows[0].misread == 1);
    REQUIRE(rows[0].acrossMm == Approx(1.5)); // of the two read strokes with an across error
    REQUIRE(rows[0].misreadAs == std::map<std::string, int> { { "brow", 1 } });
    REQUIRE(rows[1].feature == "silhouette");
    REQUIRE(rows[1].read == 0);
    REQUIRE(rows[1].acrossMm == 0);
    REQUIRE(rows[2].view == "front");
    REQUIRE(rows[2].feature == "lip_upper");
    REQUIRE(rows[2].acrossMm == Approx(0.5));
    REQUIRE(evaluation::readingsByFeature({}).empty());
}

TEST_CASE("stroke_eval: the diagnostics: mapped vertices at their true positions rebuild better, and the errors of the mapping")
{
    const evaluation::StrokeEvalData d = smallData();
    evaluation::StrokeEvalOptions o;
    o.views = { { "front", { 0, 0 } } };
    o.mappers = { sketch::MapperKind::Hmm };
    o.params = sketch::MapperParams::thesis(); // 3D observations, so that the true depth changes them
    const evaluation::StrokeEvalRecord read = firstRecord(d, o, evaluation::StrokeOracle::None);
    const evaluation::StrokeEvalRecord depth = firstRecord(d, o, evaluation::StrokeOracle::TrueDepth);
    const evaluation::StrokeEvalRecord truth = firstRecord(d, o, evaluation::StrokeOracle::TruePosition);
    INFO("read " << read.ratio << ", true depth " << depth.ratio << ", true position " << truth.ratio);
    CHECK(truth.meanMm < depth.meanMm);
    CHECK(depth.meanMm < read.meanMm);
    // The mapping's errors are measured before any oracle, and are those of a real mapping.
    CHECK(read.planeMm > 0);
    CHECK(read.depthMm > 0);
    CHECK(read.within1Mm <= read.within3Mm);
    CHECK(read.within3Mm > 0);
    CHECK(read.within3Mm <= 1);
    // The thesis' observations pin the stroke point, not across the stroke: no across error.
    CHECK(read.acrossMm == 0);
    // The defaults pin across the stroke: that error is one component of the error in the view
    // plane, so smaller than it (the rest lies along the stroke).
    o.params = {};
    const evaluation::StrokeEvalRecord across = evaluation::evaluateStrokes(test::device(), d, o).records.at(0);
    CHECK(across.acrossMm > 0);
    CHECK(across.acrossMm < across.planeMm);
    // Strokes read as a whole onto another line: few for strokes drawn on the lines, most for
    // strokes jittered by 20 px (about 5 mm), whose points are read where they were drawn.
    CHECK(read.misread == 0); // no observation across the stroke to judge by
    CHECK(across.misread < 0.2);
    o.simulate.noisePx = 20;
    const evaluation::StrokeEvalRecord jittered = evaluation::evaluateStrokes(test::device(), d, o).records.at(0);
    INFO("misread: " << across.misread << " at 1 px, " << jittered.misread << " at 20 px");
    CHECK(jittered.misread > 0.5);
    CHECK(evaluation::parseStrokeOracle("true-depth") == evaluation::StrokeOracle::TrueDepth);
    REQUIRE_THROWS_WITH(evaluation::parseStrokeOracle("truth"), Catch::Contains("'truth'"));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("stroke_eval: the contour oracles: the traced vertices across their contour, and at their image, rebuild better still")
{
    // Without jitter: a row across a jittered stroke leaks the position along it (stroke_eval.h).
    const evaluation::StrokeEvalData d = smallData();
    evaluation::StrokeEvalOptions o;
    o.views = { { "34", { 45, 0 } } };
    o.allViews = false;
    o.mappers = { sketch::MapperKind::Hmm };
    o.simulate.noisePx = 0;
    const evaluation::StrokeEvalRecord read = firstRecord(d, o, evaluation::StrokeOracle::None);
    const evaluation::StrokeEvalRecord curve = firstRecord(d, o, evaluation::StrokeOracle::TrueCurve);
    const evaluation::StrokeEvalRecord image = firstRecord(d, o, evaluation::StrokeOracle::TrueImage);
    INFO("read " << read.ratio << ", true curve " << curve.ratio << ", true image " << image.ratio);
    CHECK(curve.meanMm < read.meanMm);
    CHECK(image.meanMm < curve.meanMm);
    CHECK(evaluation::parseStrokeOracle("true-curve") == evaluation::StrokeOracle::TrueCurve);
    CHECK(evaluation::parseStrokeOracle("true-image") == evaluation::StrokeOracle::TrueImage);
    REQUIRE_THROWS_WITH(evaluation::parseStrokeOracle("curve"), Catch::Contains("true-curve"));
    REQUIRE_NO_VALIDATION_MESSAGES();
}

TEST_CASE("stroke_eval: no test faces, no mappers or another topology are refused")
{
    evaluation::StrokeEvalData d = smallData();
    evaluation::StrokeEvalOptions o;
    o.mappers.clear();
    REQUIRE_THROWS_WITH(evaluation::evaluateStrokes(test::device(), d, o), Catch::Contains("one mapper"));
    o = {};
    d.testFaces.back().V.conservativeResize(d.testFaces.back().V.rows() - 1, 3);
    REQUIRE_THROWS_WITH(evaluation::evaluateStrokes(test::device(), d, o), Catch::Contains("test2") && Catch::Contains("topology"));
    d.testFaces.clear();
    d.testNames.clear();
    REQUIRE_THROWS_WITH(evaluation::evaluateStrokes(test::device(), d, o), Catch::Contains("test faces"));
}

// The tracking model (thesis 4.6.4, 4.7.3) on a small trained model with hand-made readings:
// exact undo, oversketching, multi-view combination, symmetry and bad input.
#include "sketch/tracking.h"

#include "core/error.h"
#include "model/head_model.h"
#include "model/trained.h"
#include "sketch/simulate.h"
#include "sketch/symmetry.h"

#include <algorithm>
#include <iostream>

using namespace facesketch;
using namespace facesketch::sketch;

namespace {

const Eigen::Matrix<double, 2, 3> kFront = (Eigen::Matrix<double, 2, 3>() << 1, 0, 0, 0, 1, 0).finished();
// Seen from the face's left (camera on +x): screen x along -z, y up.
const Eigen::Matrix<double, 2, 3> kProfile = (Eigen::Matrix<double, 2, 3>() << 0, 0, -1, 0, 1, 0).finished();

// The skin vertices of the labelled contours whose name starts with `prefix`.
std::vector<std::uint32_t> contourVertices(const std::string& prefix)
{
    const auto& t = test::trainedSynth();
    const dataset::Component& skin = *t.dataset.manifest.component("skin");
    std::vector<std::uint32_t> out;
    for (const auto& [name, path] : skinContours(t.dataset.manifest.contours, skin.begin, skin.end))
        if (name.rfind(prefix, 0) == 0)
            for (int v : path)
                if (std::find(out.begin(), out.end(), static_cast<std::uint32_t>(v)) == out.end())
                    out.push_back(static_cast<std::uint32_t>(v));
    return out;
}

// A reading that pins `vertices` where test face `face` has them (in the view plane of P, or in
// 3D when P is zero), shifted by `offset` mm.
StrokeReading reading(const std::vector<std::uint32_t>& vertices, int face, const Eigen::Matrix<double, 2, 3>& P,
    const Eigen::Vector3d& offset = Eigen::Vector3d::Zero())
{
    const auto& t = test::trainedSynth();
    StrokeReading r;
    r.viewPlane = P;
    const bool plane = !P.isZero();
    for (size_t i = 0; i < vertices.size(); ++i) {
        VertexObservation o;
        o.vertex = vertices[i];
        o.position = t.testSkin.row(face).segment<3>(3 * vertices[i]).transpose() + offset;
        o.viewPlaneOnly = plane;
        o.strokePoint = static_cast<int>(i);
        r.observations.push_back(o);
    }
    return r;
}

double meanError(const Eigen::VectorXd& face, int testFace, const std::vector<std::uint32_t>& vertices)
{
    const auto& t = test::trainedSynth();
    double sum = 0;
    for (std::uint32_t v : vertices)
        sum += (face.segment<3>(3 * v) - t.testSkin.row(testFace).segment<3>(3 * v).transpose()).norm();
    return sum / static_cast<double>(vertices.size());
}

// A constraint pinning x's image in the view plane of P, each row with `variance` (mm^2).
VertexConstraint viewConstraint(const Eigen::Matrix<double, 2, 3>& P, const Eigen::Vector3d& x, double variance = 0.0)
{
    VertexConstraint c;
    c.rows = 2;
    c.A.topRows<2>() = P;
    c.b.head<2>() = P * x;
    c.noise.head<2>().setConstant(variance);
    return c;
}

bool sameState(const TrackingState& a, const TrackingState& b)
{
    if (a.strokes != b.strokes || a.face.size() != b.face.size() || a.constraints.size() != b.constraints.size())
        return false;
    // Bitwise: undo must restore, not recompute approximately.
    if (std::memcmp(a.face.data(), b.face.data(), sizeof(double) * static_cast<size_t>(a.face.size())) != 0)
        return false;
    for (size_t v = 0; v < a.constraints.size(); ++v) {
        if (a.constraints[v].size() != b.constraints[v].size())
            return false;
        for (size_t i = 0; i < a.constraints[v].size(); ++i) {
            const VertexConstraint &x = a.constraints[v][i], &y = b.constraints[v][i];
            if (x.rows != y.rows || x.stroke != y.stroke || x.A != y.A || x.b != y.b || x.mirrored != y.mirrored)
                return false;
        }
    }
    return true;
}

} // namespace

TEST_CASE("tracking: starts at the mean face with nothing observed")
{
    const auto& t = test::trainedSynth();
    const TrackingModel tracking(t.model);
    REQUIRE(tracking.face() == t.model.meanFace);
    REQUIRE(tracking.strokes() == 0);
    REQUIRE(tracking.observedVertices() == 0);
    REQUIRE(tracking.faceMesh().V.rows() == t.model.vertexCount());
}

TEST_CASE("tracking: a stroke moves the face towards the face it traces")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip");
    REQUIRE(lips.size() >= 8);
    TrackingModel tracking(t.model);
    tracking.apply(reading(lips, 0, kFront));
    REQUIRE(tracking.strokes() == 1);
    REQUIRE(tracking.observedVertices() == static_cast<int>(lips.size()));
    const double before = meanError(t.model.meanFace, 0, lips);
    const double after = meanError(tracking.face(), 0, lips);
    INFO("lip error " << before << " mm -> " << after << " mm");
    REQUIRE(after < 0.6 * before);
}

TEST_CASE("tracking: undo is exact, the state after k strokes is the same reached directly or by undoing")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip"), brows = contourVertices("eyebrow"), eyes = contourVertices("eye_socket");
    REQUIRE(!brows.empty());
    REQUIRE(!eyes.empty());
    const std::vector<StrokeReading> strokes
        = { reading(lips, 1, kFront), reading(brows, 1, kProfile), reading(eyes, 2, kFront), reading(lips, 3, kFront) };

    std::vector<TrackingState> direct; // direct[k]: the state after k strokes from scratch
    for (size_t k = 0; k <= strokes.size(); ++k) {
        TrackingModel fresh(t.model);
        for (size_t i = 0; i < k; ++i)
            fresh.apply(strokes[i]);
        direct.push_back(fresh.state());
    }
    REQUIRE_FALSE(sameState(direct[3], direct[4])); // the last stroke changes something

    TrackingModel tracking(t.model);
    REQUIRE_FALSE(tracking.undo());
    for (const StrokeReading& s : strokes)
        tracking.apply(s);
    REQUIRE(sameState(tracking.state(), direct[4]));
    for (int k = 3; k >= 0; --k) {
        REQUIRE(tracking.undo());
        REQUIRE(sameState(tracking.state(), direct[static_cast<size_t>(k)]));
    }
    REQUIRE_FALSE(tracking.undo());
    REQUIRE(tracking.redo());
    REQUIRE(tracking.redo());
    REQUIRE(sameState(tracking.state(), direct[2]));
    // A new stroke after undoing forgets the undone ones.
    tracking.apply(strokes[2]);
    REQUIRE(sameState(tracking.state(), direct[3]));
    REQUIRE_FALSE(tracking.redo());
}

TEST_CASE("tracking: oversketching a feature replaces it instead of averaging the two")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip");
    // The same lips drawn twice from the front, the second time 4 mm lower: the result is the
    // second drawing alone.
    TrackingModel twice(t.model);
    twice.apply(reading(lips, 0, kFront));
    twice.apply(reading(lips, 0, kFront, { 0, -4, 0 }));
    TrackingModel once(t.model);
    once.apply(reading(lips, 0, kFront, { 0, -4, 0 }));
    REQUIRE((twice.face() - once.face()).cwiseAbs().maxCoeff() < 1e-9);
    for (std::uint32_t v : lips) {
        REQUIRE(twice.state().constraints[v].size() == 1);
        REQUIRE(twice.state().constraints[v][0].stroke == 2);
    }
    // Other features stay: a brow stroke, then the lips redrawn, keeps the brow's constraints.
    const auto brows = contourVertices("eyebrow");
    TrackingModel mixed(t.model);
    mixed.apply(reading(brows, 0, kFront));
    mixed.apply(reading(lips, 0, kFront));
    for (std::uint32_t v : brows)
        REQUIRE(mixed.state().constraints[v].size() == 1);
}

TEST_CASE("tracking: what was drawn before, seen from a view: strokes of similar views and 3D constraints, less the stroke left out")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip");
    const auto brows = contourVertices("eyebrow");
    const auto eyes = contourVertices("eye_socket");
    const Eigen::Vector3d front(0, 0, 1), side(1, 0, 0), near(std::sin(0.35), 0, std::cos(0.35)); // 20 degrees from the front
    TrackingModel tracking(t.model);
    const auto count = [](const std::vector<char>& flags) { return std::count(flags.begin(), flags.end(), 1); };
    REQUIRE(tracking.drawnVertices(front).size() == static_cast<size_t>(t.model.vertexCount()));
    REQUIRE(count(tracking.drawnVertices(front)) == 0);
    tracking.apply(reading(lips, 0, kFront));    // stroke 1
    tracking.apply(reading(brows, 0, kProfile)); // stroke 2
    const auto in
        = [](const std::vector<std::uint32_t>& set, std::uint32_t v) { return std::find(set.begin(), set.end(), v) != set.end(); };
    for (std::uint32_t v : eyes) // the counts below hold for disjoint lines
        REQUIRE_FALSE((in(lips, v) || in(brows, v)));
    for (std::uint32_t v : brows)
        REQUIRE_FALSE(in(lips, v));
    for (const Eigen::Vector3d& axis : { front, near }) {
        const std::vector<char> d = tracking.drawnVertices(axis);
        REQUIRE(count(d) == static_cast<std::ptrdiff_t>(lips.size()));
        for (std::uint32_t v : lips)
            REQUIRE(d[v] == 1);
    }
    const std::vector<char> fromSide = tracking.drawnVertices(side);
    REQUIRE(count(fromSide) == static_cast<std::ptrdiff_t>(brows.size()));
    for (std::uint32_t v : brows)
        REQUIRE(fromSide[v] == 1);
    // Stroke 1 left out (a refinement pass of it reads against its own reading).
    REQUIRE(count(tracking.drawnVertices(front, 1)) == 0);
    REQUIRE(count(tracking.drawnVertices(side, 1)) == static_cast<std::ptrdiff_t>(brows.size()));
    // A 3D constraint is drawn as seen from every view.
    tracking.apply(reading(eyes, 0, Eigen::Matrix<double, 2, 3>::Zero())); // stroke 3
    for (const Eigen::Vector3d& axis : { front, side }) {
        const std::vector<char> d = tracking.drawnVertices(axis);
        for (std::uint32_t v : eyes)
            REQUIRE(d[v] == 1);
        REQUIRE(count(d) == static_cast<std::ptrdiff_t>(eyes.size() + (axis == front ? lips.size() : brows.size())));
    }
}

TEST_CASE("tracking: a redrawn line supersedes the old one where it passes, mapped to other vertices or not")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip_upper_outer");
    REQUIRE(lips.size() >= 6);
    TrackingModel tracking(t.model);
    tracking.apply(reading(lips, 0, kFront));
    // The second drawing pins every other vertex only, but its line passes over all of them.
    std::vector<std::uint32_t> half;
    for (size_t i = 0; i < lips.size(); i += 2)
        half.push_back(lips[i]);
    StrokeReading again = reading(half, 1, kFront);
    for (std::uint32_t v : lips)
        again.worldPoints.push_back(tracking.face().segment<3>(3 * v));
    tracking.apply(again);
    for (std::uint32_t v : lips)
        for (const VertexConstraint& c : tracking.state().constraints[v])
            REQUIRE(c.stroke == 2);
    // A line drawn far from the lips (the brows) leaves the lips' constraints alone.
    const auto brows = contourVertices("eyebrow");
    StrokeReading brow = reading(brows, 1, kFront);
    for (std::uint32_t v : brows)
        brow.worldPoints.push_back(tracking.face().segment<3>(3 * v));
    tracking.apply(brow);
    for (size_t i = 0; i < lips.size(); i += 2)
        REQUIRE(tracking.state().constraints[lips[i]].size() == 1);
}

TEST_CASE("tracking: strokes from two views combine into 3D measurements and a better face")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip");
    TrackingModel front(t.model);
    front.apply(reading(lips, 4, kFront));
    TrackingModel both(t.model);
    both.apply(reading(lips, 4, kFront));
    both.apply(reading(lips, 4, kProfile));
    for (std::uint32_t v : lips)
        REQUIRE(both.state().constraints[v].size() == 2);
    // Every lip vertex is then measured in 3D: 3 values each.
    REQUIRE(both.observations().size() == 3 * static_cast<Eigen::Index>(lips.size()));
    REQUIRE(front.observations().size() == 2 * static_cast<Eigen::Index>(lips.size()));
    const double errorFront = meanError(front.face(), 4, lips), errorBoth = meanError(both.face(), 4, lips);
    INFO("front " << errorFront << " mm, front + profile " << errorBoth << " mm");
    REQUIRE(errorBoth < errorFront);
}

TEST_CASE("tracking: two view-plane constraints combine by least squares")
{
    const Eigen::Vector3d x(3, -2, 7);
    const VertexConstraint a = viewConstraint(kFront, x);
    const VertexConstraint b = viewConstraint(kProfile, x + Eigen::Vector3d(0, 1, 0)); // y disagrees by 1 mm
    stats::Observations obs;
    addCombined(obs, 5, { a, b });
    REQUIRE(obs.size() == 3);
    const Eigen::VectorXd y = obs.values();
    REQUIRE(y[0] == Approx(3));
    REQUIRE(y[1] == Approx(-1.5));
    REQUIRE(y[2] == Approx(7));
    // Two constraints of one view (rows spanning a plane only) stay a view-plane measurement.
    stats::Observations same;
    addCombined(same, 5, { a, a });
    REQUIRE(same.size() == 2);
    // Two across-stroke constraints along one direction stay one measurement along it.
    VertexConstraint c, e;
    c.rows = e.rows = 1;
    c.A.row(0) = e.A.row(0) = Eigen::RowVector3d(0, 1, 0);
    c.b[0] = 2;
    e.b[0] = 3;
    stats::Observations along;
    addCombined(along, 5, { c, e });
    REQUIRE(along.size() == 1);
    REQUIRE(std::abs(along.values()[0]) == Approx(2.5));
}

TEST_CASE("tracking: an across-stroke observation pins the vertex across the stroke only, not along it")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip");
    // A horizontal stroke seen from the front: across it is y.
    const Eigen::Vector3d across(0, 1, 0);
    auto acrossReading = [&](const Eigen::Vector3d& offset, bool planeOnly) {
        StrokeReading r = reading(lips, 0, kFront, offset);
        for (VertexObservation& o : r.observations) {
            o.viewPlaneOnly = planeOnly;
            o.acrossStroke = across;
        }
        return r;
    };
    for (bool planeOnly : { true, false }) {
        INFO("view-plane only " << planeOnly);
        TrackingModel a(t.model), b(t.model);
        a.apply(acrossReading(Eigen::Vector3d::Zero(), planeOnly));
        b.apply(acrossReading(Eigen::Vector3d(2.5, 0, 0), planeOnly)); // slid along the stroke
        CHECK((a.face() - b.face()).cwiseAbs().maxCoeff() < 1e-9);
        const auto& c = a.state().constraints[lips[0]];
        REQUIRE(c.size() == 1);
        CHECK(c[0].rows == (planeOnly ? 1 : 2));
        // It moves the lips towards the face they trace.
        CHECK(meanError(a.face(), 0, lips) < meanError(t.model.meanFace, 0, lips));
    }
    // A direction along the view axis is refused, leaving the state as it was.
    TrackingModel tracking(t.model);
    tracking.apply(reading(lips, 1, kFront));
    const TrackingState before = tracking.state();
    StrokeReading bad = acrossReading(Eigen::Vector3d::Zero(), true);
    bad.observations[2].acrossStroke = Eigen::Vector3d(0, 0, 1);
    REQUIRE_THROWS_WITH(tracking.apply(bad), Catch::Contains("observations[2].acrossStroke") && Catch::Contains("view plane"));
    REQUIRE(sameState(tracking.state(), before));
}

TEST_CASE("tracking: bad readings throw and leave the state exactly as it was")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip");
    TrackingModel tracking(t.model);
    tracking.apply(reading(lips, 0, kFront));
    tracking.apply(reading(lips, 1, kProfile));
    tracking.undo(); // one stroke to redo, which a failed apply must not forget
    const TrackingState before = tracking.state();

    StrokeReading empty;
    empty.viewPlane = kFront;
    REQUIRE_THROWS_WITH(tracking.apply(empty), Catch::Contains("pins no vertex"));
    StrokeReading outside = reading(lips, 2, kFront);
    outside.observations[3].vertex = static_cast<std::uint32_t>(t.model.vertexCount());
    REQUIRE_THROWS_WITH(tracking.apply(outside), Catch::Contains("observations[3].vertex") && Catch::Contains("outside"));
    StrokeReading nan = reading(lips, 2, kFront);
    nan.observations[1].position.y() = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(tracking.apply(nan), Catch::Contains("observations[1].position") && Catch::Contains("not finite"));
    StrokeReading twice = reading(lips, 2, kFront);
    twice.observations[2].vertex = twice.observations[0].vertex;
    REQUIRE_THROWS_WITH(tracking.apply(twice), Catch::Contains("observed twice"));
    StrokeReading skew = reading(lips, 2, kFront);
    skew.viewPlane(0, 1) = 0.5;
    REQUIRE_THROWS_WITH(tracking.apply(skew), Catch::Contains("not orthonormal"));

    REQUIRE(sameState(tracking.state(), before));
    REQUIRE(tracking.redo());
}

TEST_CASE("tracking: with symmetry a stroke on one side pins the mirror vertices too")
{
    const auto& t = test::trainedSynth();
    const dataset::Component& skin = *t.dataset.manifest.component("skin");
    Mesh mean;
    mean.F = t.model.triangles;
    mean.V.resize(t.model.vertexCount(), 3);
    for (Eigen::Index v = 0; v < mean.V.rows(); ++v)
        mean.V.row(v) = t.model.meanFace.segment<3>(3 * v).transpose();
    const MirrorMap mirror = MirrorMap::find(mean, skinLandmarks(t.dataset.manifest.landmarks, skin.begin, skin.end), "mean face");
    // The brow on the face's left only (x > the plane).
    std::vector<std::uint32_t> left;
    for (std::uint32_t v : contourVertices("eyebrow"))
        if (mean.V(v, 0) > mirror.check().planeX + 5)
            left.push_back(v);
    REQUIRE(left.size() >= 3);
    ApplyOptions options;
    options.mirror = &mirror;
    const StrokeReading brow = reading(left, 0, kFront);
    for (double noise : { TrackingOptions {}.planeNoiseMm, 0.0 }) {
        INFO("plane noise " << noise << " mm");
        TrackingOptions to;
        to.planeNoiseMm = noise;
        TrackingModel tracking(t.model, to);
        tracking.apply(brow, options);
        REQUIRE(tracking.observedVertices() == static_cast<int>(2 * left.size()));
        for (size_t i = 0; i < left.size(); ++i) {
            const std::uint32_t v = left[i];
            const auto& c = tracking.state().constraints[mirror.partner(v)];
            REQUIRE(c.size() == 1);
            REQUIRE(c[0].mirrored);
            const Eigen::Vector3d image = mirror.mirror(tracking.face().segment<3>(3 * v));
            const Eigen::Vector3d partner = tracking.face().segment<3>(3 * mirror.partner(v));
            INFO("vertex " << v << " partner " << mirror.partner(v));
            if (noise > 0) // the mirror image of what the stroke measured
                REQUIRE((c[0].A.topRows<2>() * mirror.mirror(brow.observations[i].position) - c[0].b.head<2>()).norm() < 1e-9);
            else // exact rows: the rebuilt partner's image, projected onto the face space
                REQUIRE((c[0].A.topRows<2>() * partner - c[0].b.head<2>()).norm() < 1e-9);
            REQUIRE((image - partner).head<2>().norm() < 1.5);
        }
    }
}

TEST_CASE("tracking: noisy constraints combine by their weights and keep what the stroke measured")
{
    const Eigen::Vector3d x(3, -2, 7);
    const VertexConstraint a = viewConstraint(kFront, x, 1.0);
    const VertexConstraint b = viewConstraint(kProfile, x + Eigen::Vector3d(0, 1, 0), 4.0); // y disagrees by 1 mm
    stats::Observations obs;
    addCombined(obs, 5, { a, b });
    REQUIRE(obs.size() == 3);
    // Along x only the front measures (variance 1), along z only the profile (4); y is the
    // inverse-variance mean of -2 and -1 with variance 1 / (1 + 1/4).
    const Eigen::MatrixXd P = obs.denseP(18).middleCols<3>(15);
    const Eigen::Vector3d position = P.transpose() * obs.values();
    CHECK((position - Eigen::Vector3d(3, -1.8, 7)).norm() < 1e-9);
    const Eigen::Matrix3d covariance = P.transpose() * obs.noiseVariances().asDiagonal() * P;
    CHECK((covariance - Eigen::Vector3d(1.0, 0.8, 4.0).asDiagonal().toDenseMatrix()).norm() < 1e-9);
    // A noisy row beside an exact one (two across-stroke rows of one direction): the exact one wins.
    VertexConstraint exact = a, loose = a;
    exact.rows = loose.rows = 1;
    exact.noise.setZero();
    loose.b[0] = 5;
    stats::Observations pinned;
    addCombined(pinned, 5, { exact, loose });
    REQUIRE(pinned.size() == 1);
    CHECK(std::abs(pinned.values()[0]) == Approx(3).margin(1e-6));
    CHECK(pinned.noiseVariances()[0] < 1e-7);

    // In the tracking model, a noisy row keeps the stroke's value after later strokes rebuild
    // the face (step 4 moves only exact rows).
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip"), brows = contourVertices("eyebrow");
    TrackingModel tracking(t.model);
    const StrokeReading lip = reading(lips, 2, kFront, Eigen::Vector3d(0, 0.5, 0));
    tracking.apply(lip);
    tracking.apply(reading(brows, 2, kFront));
    for (size_t i = 0; i < lips.size(); ++i) {
        const auto& c = tracking.state().constraints[lips[i]];
        REQUIRE(c.size() == 1);
        CHECK((c[0].b.head<2>() - kFront * lip.observations[i].position).norm() < 1e-12);
        CHECK(c[0].noise.head<2>() == Eigen::Vector2d::Constant(std::pow(TrackingOptions {}.planeNoiseMm, 2)));
    }
}

TEST_CASE("tracking: with the robust passes points read onto the wrong vertices bend the face less")
{
    const auto& t = test::trainedSynth();
    const auto lips = contourVertices("lip");
    REQUIRE(lips.size() >= 8);
    // The lips where a test face has them, but every fourth point read 8 mm off (wrong
    // candidates). The claim is over all 10 test faces together. It was on face 3 alone, where
    // the robust passes undid more than half the harm; over all 10 they undo 39% (0.37 of
    // 0.95 mm, the generator before its means were fitted to ICT) and 36% with them (0.35 of
    // 0.97 mm), where the wrong points do face 3 alone only 0.01 mm of harm: one face is no
    // premise.
    std::vector<bool> wrong(lips.size(), false);
    for (size_t i = 0; i < lips.size(); i += 4)
        wrong[i] = true;
    // The mean error of the lip vertices read rightly, summed over the faces.
    double base = 0, plain = 0, robust = 0;
    for (int face = 0; face < static_cast<int>(t.testSkin.rows()); ++face) {
        const StrokeReading clean = reading(lips, face, kFront);
        StrokeReading wrongly = clean;
        for (size_t i = 0; i < lips.size(); ++i)
            if (wrong[i])
                wrongly.observations[i].position += Eigen::Vector3d(0, 8, 0);
        auto errorOfOthers = [&](const StrokeReading& r, int passes) {
            TrackingOptions o;
            o.robustPasses = passes;
            TrackingModel tracking(t.model, o);
            tracking.apply(r);
            double sum = 0;
            for (size_t i = 0; i < lips.size(); ++i)
                if (!wrong[i])
                    sum += (tracking.face().segment<3>(3 * lips[i]) - t.testSkin.row(face).segment<3>(3 * lips[i]).transpose()).norm();
            return sum / static_cast<double>(std::count(wrong.begin(), wrong.end(), false));
        };
        base += errorOfOthers(clean, 0);
        plain += errorOfOthers(wrongly, 0);
        robust += errorOfOthers(wrongly, 2);
    }
    const double faces = static_cast<double>(t.testSkin.rows());
    base /= faces;
    plain /= faces;
    robust /= faces;
    std::cout << "tracking: lip error over " << faces << " faces: " << base << " mm read rightly, " << plain
              << " mm with the wrong points, " << robust << " mm with the robust passes\n";
    INFO("lip error over " << faces << " faces: " << base << " mm read rightly; with the wrong points " << plain << " mm, " << robust
                           << " mm with the robust passes");
    REQUIRE(faces >= 5);
    REQUIRE(plain > base + 0.1);                       // the wrong points do harm ...
    CHECK(robust - base < 2.0 / 3.0 * (plain - base)); // ... of which the robust passes undo more than a third
    TrackingOptions bad;
    bad.robustK = 0;
    REQUIRE_THROWS_WITH(TrackingModel(t.model, bad), Catch::Contains("robustK"));
    bad = {};
    bad.planeNoiseMm = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(TrackingModel(t.model, bad), Catch::Contains("planeNoiseMm"));
    bad = {};
    bad.supersedeRadius = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(TrackingModel(t.model, bad), Catch::Contains("supersedeRadius"));
    bad = {};
    bad.supersedeAngleDeg = std::numeric_limits<double>::infinity();
    REQUIRE_THROWS_WITH(TrackingModel(t.model, bad), Catch::Contains("supersedeAngleDeg"));
}

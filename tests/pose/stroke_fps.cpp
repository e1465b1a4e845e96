// Feature points from strokes (thesis 5.3): strokes along a pose's own lip contour, hand-made
// clusters with known answers for the endpoint rules, and bad input.
#include "pose/stroke_fps.h"

#include "core/error.h"
#include "dataset/synth/face_generator.h"
#include "dataset/synth/face_params.h"
#include "dataset/synth/pose_recipes.h"
#include "test_common.h"

#include <algorithm>
#include <set>

using namespace facesketch;
using namespace facesketch::pose;

namespace {

const dataset::PoseRecipe& recipe(const std::string& name)
{
    for (const auto& r : dataset::poseRecipes())
        if (r.name == name)
            return r;
    FAIL("no pose recipe " << name);
    return dataset::poseRecipes().front();
}

/// Synthetic low-resolution faces: the FP displacements of the 36 poses of identities 0-7, and
/// identity 20 (not among them) to pose.
struct SynthPoses {
    dataset::FaceTopology topology = dataset::buildFaceTopology(dataset::Resolution::Low);
    FeaturePoints fps = featurePoints(topology.labels, "synthetic topology");
    Eigen::MatrixXd training;
    dataset::FaceParams face = dataset::sampleFaceParams(1, 20);
    Vertices neutral = dataset::synthesizeFace(topology, face);

    SynthPoses()
    {
        const auto& recipes = dataset::poseRecipes();
        training.resize(8 * static_cast<Eigen::Index>(recipes.size()), 3 * fps.size());
        for (int i = 0; i < 8; ++i) {
            const dataset::FaceParams params = dataset::sampleFaceParams(1, i);
            const Eigen::VectorXd rest = fps.gather(dataset::synthesizeFace(topology, params));
            for (std::size_t p = 0; p < recipes.size(); ++p)
                training.row(i * static_cast<Eigen::Index>(recipes.size()) + static_cast<Eigen::Index>(p))
                    = (fps.gather(dataset::synthesizeFace(topology, params, recipes[p].actions)) - rest).transpose();
        }
    }
};

Eigen::Matrix<double, 2, 3> frontPlane()
{
    Eigen::Matrix<double, 2, 3> P;
    P << 1, 0, 0, 0, 1, 0;
    return P;
}

std::set<std::string> namesOf(const FpReading& reading)
{
    std::set<std::string> names;
    for (const auto& fp : reading.fps)
        names.insert(fp.name);
    return names;
}

/// Hand-made clusters: every sketchable FP far from the others (a 100 mm grid), except the
/// lips: upper lip along y = 0 (8.4 at x = -30, 8.5 -12, 8.9 -6, 8.1 0, 8.10 6, 8.6 12, 8.3 30),
/// lower lip along y = -20. Training moves every FP by 1 mm along x or y, so each cluster has
/// covariance diag(0.5, 0.5, 0) + 1.5^2 I.
struct HandMade {
    FeaturePoints fps;
    Vertices neutral;
    Eigen::MatrixXd training;

    HandMade()
    {
        const std::map<std::string, Eigen::Vector3d> lips = { { "8.4", { -30, 0, 0 } }, { "8.5", { -12, 0, 0 } }, { "8.9", { -6, 0, 0 } },
            { "8.1", { 0, 0, 0 } }, { "8.10", { 6, 0, 0 } }, { "8.6", { 12, 0, 0 } }, { "8.3", { 30, 0, 0 } }, { "8.7", { -15, -20, 0 } },
            { "8.2", { 0, -20, 0 } }, { "8.8", { 15, -20, 0 } } };
        std::vector<std::string> names;
        for (const auto& group : fpGroups())
            for (const auto& name : group.fps)
                if (std::find(names.begin(), names.end(), name) == names.end())
                    names.push_back(name);
        std::sort(names.begin(), names.end(), fdpLess);
        neutral.resize(static_cast<Eigen::Index>(names.size()), 3);
        for (std::size_t i = 0; i < names.size(); ++i) {
            fps.names.push_back(names[i]);
            fps.vertices.push_back(static_cast<int>(i));
            const auto lip = lips.find(names[i]);
            neutral.row(static_cast<Eigen::Index>(i)) = lip != lips.end()
                ? lip->second.transpose()
                : Eigen::RowVector3d(100.0 * (1 + static_cast<double>(i % 6)), 100.0 * static_cast<double>(1 + i / 6), 0);
        }
        training = Eigen::MatrixXd::Zero(4, 3 * fps.size());
        for (Eigen::Index f = 0; f < fps.size(); ++f) {
            training(0, 3 * f) = 1;
            training(1, 3 * f) = -1;
            training(2, 3 * f + 1) = 1;
            training(3, 3 * f + 1) = -1;
        }
    }
};

PoseStrokePoints line(double x0, double x1, double y, double step)
{
    PoseStrokePoints stroke;
    stroke.plane = frontPlane();
    for (double x = x0; x <= x1 + 1e-9; x += step)
        stroke.world.emplace_back(x, y, 0);
    return stroke;
}

} // namespace

TEST_CASE("stroke fps: a stroke along the open smile's upper lip finds the upper lip's FPs where the smile has them")
{
    const SynthPoses s;
    REQUIRE(s.fps.size() == 46);
    const FpClusters clusters = fpClusters(s.fps, s.training, s.neutral);
    REQUIRE(clusters.size() == 32);
    const Vertices smile = dataset::synthesizeFace(s.topology, s.face, recipe("smile_open").actions);
    PoseStrokePoints stroke;
    stroke.plane = frontPlane();
    for (int v : s.topology.labels.contours.at("lip_upper_outer"))
        stroke.world.emplace_back(smile.row(v).transpose());
    const FpReading reading = identifyFps(clusters, { stroke });
    REQUIRE(reading.strokeGroup == std::vector<std::string> { "upper_lip" });
    const std::set<std::string> found = namesOf(reading);
    INFO("found " << found.size() << " FPs");
    // The corners and the midpoint lie on the contour; every FP found is an upper-lip FP.
    for (const std::string name : { "8.1", "8.3", "8.4" })
        REQUIRE(found.count(name) == 1);
    const auto& upper = fpGroups()[6];
    REQUIRE(upper.name == "upper_lip");
    for (const auto& fp : reading.fps) {
        INFO(fp.name);
        REQUIRE(std::find(upper.fps.begin(), upper.fps.end(), fp.name) != upper.fps.end());
        // Where the smile has that FP, seen from the front (the depth is the completion's).
        const Eigen::Vector3d target = smile.row(s.fps.vertices[static_cast<std::size_t>(fp.fp)]).transpose();
        REQUIRE((frontPlane() * (fp.position - target)).norm() < 3.0);
    }
    // The open smile's corners are far from the neutral ones: the strokes did not just find the rest face.
    const int corner = s.fps.vertices[static_cast<std::size_t>(s.fps.index("8.3"))];
    REQUIRE((smile.row(corner) - s.neutral.row(corner)).norm() > 4.0);

    // The observations hand the completion the FPs' sketch-plane displacements (2 each).
    const stats::Observations observed = poseObservations(s.fps, s.neutral, reading);
    REQUIRE(observed.size() == 2 * static_cast<Eigen::Index>(reading.fps.size()));
    Eigen::VectorXd expected(observed.size());
    for (std::size_t i = 0; i < reading.fps.size(); ++i)
        expected.segment<2>(2 * static_cast<Eigen::Index>(i)) = frontPlane()
            * (reading.fps[i].position - s.neutral.row(s.fps.vertices[static_cast<std::size_t>(reading.fps[i].fp)]).transpose());
    REQUIRE((observed.values() - expected).norm() < 1e-12);
}

TEST_CASE("stroke fps: the lower lip and a lowered brow go to their own groups")
{
    const SynthPoses s;
    const FpClusters clusters = fpClusters(s.fps, s.training, s.neutral);
    const Vertices anger = dataset::synthesizeFace(s.topology, s.face, recipe("anger").actions);
    std::vector<PoseStrokePoints> strokes(2);
    for (auto& stroke : strokes)
        stroke.plane = frontPlane();
    for (int v : s.topology.labels.contours.at("lip_lower_outer"))
        strokes[0].world.emplace_back(anger.row(v).transpose());
    for (int v : s.topology.labels.contours.at("eyebrow_l"))
        strokes[1].world.emplace_back(anger.row(v).transpose());
    const FpReading reading = identifyFps(clusters, strokes);
    REQUIRE(reading.strokeGroup == std::vector<std::string> { "lower_lip", "brow_left" });
    const std::set<std::string> found = namesOf(reading);
    REQUIRE(found.count("8.2") == 1);
    REQUIRE(found.count("4.3") == 1);
    for (const auto& fp : reading.fps)
        REQUIRE((fp.name.rfind("8.", 0) == 0 || fp.name.rfind("4.", 0) == 0));
}

TEST_CASE("stroke fps: short strokes' endpoints are nudged to the corners, at the endpoints")
{
    const HandMade h;
    const FpClusters clusters = fpClusters(h.fps, h.training, h.neutral);
    // x from -22 to 22: the ends are 8 mm (Mahalanobis 4.8) from the corners and 10 mm from 8.5,
    // 8.6, so they hit nothing; moved 6 mm towards a corner they hit it.
    FpReadingOptions three; // the threshold these distances are made for
    three.maxMahalanobis = 3;
    const FpReading reading = identifyFps(clusters, { line(-22, 22, 0, 1) }, three);
    REQUIRE(reading.strokeGroup == std::vector<std::string> { "upper_lip" });
    REQUIRE(namesOf(reading) == std::set<std::string> { "8.1", "8.3", "8.4", "8.5", "8.6", "8.9", "8.10" });
    for (const auto& fp : reading.fps) {
        INFO(fp.name);
        const bool corner = fp.name == "8.3" || fp.name == "8.4";
        REQUIRE(fp.nudged == corner);
        if (corner)
            REQUIRE(fp.position.isApprox(Eigen::Vector3d(fp.name == "8.3" ? 22 : -22, 0, 0)));
        else // interior points: the stroke point at the cluster's mean
            REQUIRE((fp.position - h.neutral.row(fp.fp).transpose()).norm() < 1e-9);
    }
    FpReadingOptions noNudge = three;
    noNudge.nudgeMm = 0;
    REQUIRE(
        namesOf(identifyFps(clusters, { line(-22, 22, 0, 1) }, noNudge)) == std::set<std::string> { "8.1", "8.5", "8.6", "8.9", "8.10" });
    // Nudged 3 mm only, the ends stay 5 mm (Mahalanobis 3.0+) away: not taken.
    FpReadingOptions shortNudge = three;
    shortNudge.nudgeMm = 3;
    REQUIRE(namesOf(identifyFps(clusters, { line(-22, 22, 0, 1) }, shortNudge)).count("8.3") == 0);
}

TEST_CASE("stroke fps: an endpoint outweighs a slightly likelier interior point of the same FP")
{
    const HandMade h;
    const FpClusters clusters = fpClusters(h.fps, h.training, h.neutral);
    // The stroke starts 1 mm from 8.4's mean, then passes exactly through it.
    PoseStrokePoints stroke = line(-30, 0, 0, 1);
    stroke.world.insert(stroke.world.begin(), Eigen::Vector3d(-29, 0, 0));
    auto cornerAt = [&](const FpReadingOptions& options) {
        for (const auto& fp : identifyFps(clusters, { stroke }, options).fps)
            if (fp.name == "8.4")
                return fp.position.x();
        FAIL("8.4 not found");
        return 0.0;
    };
    FpReadingOptions weighted; // endpointWeight 2: log 2 = 0.69 beats the 0.18 density gap
    weighted.endpointWeight = 2;
    REQUIRE(cornerAt(weighted) == -29);
    FpReadingOptions flat;
    flat.endpointWeight = 1;
    REQUIRE(cornerAt(flat) == -30);
}

TEST_CASE("stroke fps: a widened lip's mid-points follow its corners (step 6), where the likeliest point leans inwards")
{
    // Training: the mouth widens or narrows (corners 8.3/8.4 by 4 mm, mid-points 8.5/8.6 by
    // 2 mm, 8.9/8.10 by 1 mm, all along x) and every FP moves 1 mm up or down.
    HandMade h;
    h.training.setZero();
    const std::map<std::string, double> widen = { { "8.3", 4 }, { "8.4", -4 }, { "8.6", 2 }, { "8.5", -2 }, { "8.10", 1 }, { "8.9", -1 } };
    for (Eigen::Index f = 0; f < h.fps.size(); ++f) {
        const auto w = widen.find(h.fps.names[static_cast<std::size_t>(f)]);
        if (w != widen.end()) {
            h.training(0, 3 * f) = w->second;
            h.training(1, 3 * f) = -w->second;
        }
        h.training(2, 3 * f + 1) = 1;
        h.training(3, 3 * f + 1) = -1;
    }
    const FpClusters clusters = fpClusters(h.fps, h.training, h.neutral);
    // 8.6's joint block with the corners: Cov(x86, x83) = 4, Cov(x86, x84) = -4.
    const int c86 = static_cast<int>(std::find(clusters.names.begin(), clusters.names.end(), "8.6") - clusters.names.begin());
    const int c83 = static_cast<int>(std::find(clusters.names.begin(), clusters.names.end(), "8.3") - clusters.names.begin());
    REQUIRE(clusters.jointCovariance(3 * c86, 3 * c83) == Approx(4.0));
    REQUIRE(clusters.jointCovariance.block<3, 3>(3 * c86, 3 * c86).isApprox(clusters.covariance[static_cast<std::size_t>(c86)]));

    // A mouth 3 mm wider at each corner than the rest face: as the training widens, 8.6 belongs
    // at x = 13.5. (The ends are 3 mm from the corners' means, close enough for even the
    // thesis-like endpoint bonus, log 2, to keep them at the ends: 3^2 / (2 x 10.25) = 0.44.)
    const PoseStrokePoints stroke = line(-33, 33, 0, 1);
    auto at = [&](const FpReadingOptions& options, const std::string& name) {
        for (const auto& fp : identifyFps(clusters, { stroke }, options).fps)
            if (fp.name == name)
                return fp;
        FAIL(name << " not found");
        return IdentifiedFp {};
    };
    FpReadingOptions thesis;
    thesis.followEnds = false;
    // Step 5 alone: the stroke point at the cluster's mean, 2 mm inwards.
    REQUIRE(at(thesis, "8.6").position.x() == 12);
    REQUIRE_FALSE(at(thesis, "8.6").conditioned);
    // Given the corners (each 3 mm out, plane x): the conditional mean is 12 + c' S^-1 y with
    // c = (4, -4), y = (3, -3) and S = [[8 + 2.25, -8], [-8, 8 + 2.25]] (minStdMm 1.5), i.e.
    // 12 + 24 / 18.25 = 13.3, and the nearest stroke point is 13.
    const IdentifiedFp followed = at({}, "8.6");
    REQUIRE(followed.conditioned);
    REQUIRE(followed.position.x() == 13);
    REQUIRE(at({}, "8.5").position.x() == -13);
    // The corners themselves are the stroke's ends, unchanged by step 6.
    REQUIRE(at({}, "8.3").position.x() == 33);
    REQUIRE_FALSE(at({}, "8.3").conditioned);
    // 8.1 does not move with the width: it stays at the centre.
    REQUIRE(at({}, "8.1").position.x() == 0);
}

TEST_CASE("stroke fps: a stroke that hits no cluster, and other bad input, are errors naming the stroke or FP")
{
    const HandMade h;
    const FpClusters clusters = fpClusters(h.fps, h.training, h.neutral);
    REQUIRE_THROWS_WITH(identifyFps(clusters, { line(-10, 10, 0, 1), line(-10, 10, -60, 1) }),
        Catch::StartsWith("pose stroke 1 hits no feature point cluster: its nearest is") && Catch::Contains("the threshold is 4"));
    PoseStrokePoints nan = line(-10, 10, 0, 1);
    nan.world[3].y() = std::nan("");
    REQUIRE_THROWS_WITH(identifyFps(clusters, { nan }), Catch::Contains("pose stroke 0: point 3 is not finite"));
    REQUIRE_THROWS_WITH(identifyFps(clusters, { PoseStrokePoints { {}, frontPlane() } }), Catch::Contains("pose stroke 0: no points"));
    PoseStrokePoints skew = line(-10, 10, 0, 1);
    skew.plane(0, 1) = 0.5;
    REQUIRE_THROWS_WITH(identifyFps(clusters, { skew }), Catch::Contains("pose stroke 0: the rows of its sketch plane"));
    FpReadingOptions bad;
    bad.endpointWeight = 0.5;
    REQUIRE_THROWS_WITH(identifyFps(clusters, { line(-10, 10, 0, 1) }, bad), Catch::Contains("endpointWeight 0.5"));

    FeaturePoints missing = h.fps;
    const int corner = missing.index("8.3");
    missing.names[static_cast<std::size_t>(corner)] = "8.30";
    REQUIRE_THROWS_WITH(fpClusters(missing, h.training, h.neutral), Catch::Contains("no feature point 8.3 "));
    REQUIRE_THROWS_WITH(fpClusters(h.fps, h.training.leftCols(9), h.neutral), Catch::Contains("9 columns"));
    Vertices nanFace = h.neutral;
    nanFace(corner, 2) = std::nan("");
    REQUIRE_THROWS_WITH(fpClusters(h.fps, h.training, nanFace), Catch::Contains("FP 8.3") && Catch::Contains("not finite"));
}

// Tests of model/head_model on a synthetic low-resolution dataset written by the test: held-out
// faces rebuilt from 15% of their vertices (random, or one feature region), the effect of the
// segment correlation, eyeballs that stay in their sockets, and the model file round trip.
// The figures are printed in mm.
#include "model/head_model.h"

#include "core/error.h"
#include "core/random.h"
#include "dataset/import_ict.h"
#include "evaluation/evaluate.h"
#include "model/head_assembly.h"
#include "model/regions.h"
#include "stats/model_file.h"
#include "trained.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <iostream>

using namespace facesketch;
using namespace facesketch::stats;
using namespace facesketch::evaluation;

namespace {

Eigen::RowVector3d centroid(const Eigen::Ref<const Eigen::RowVectorXd>& face, const std::vector<int>& vertices)
{
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (int v : vertices)
        sum += face.segment<3>(3 * v);
    return sum / static_cast<double>(vertices.size());
}

std::vector<int> range(const dataset::Component& c)
{
    std::vector<int> out;
    for (int v = c.begin; v < c.end; ++v)
        out.push_back(v);
    return out;
}

} // namespace

TEST_CASE("head_model: 15% random vertices of held-out synthetic faces give under half the mean-face error")
{
    const test::TrainedSynth& t = test::trainedSynth();
    REQUIRE(t.testSkin.rows() >= 8);
    ObserveOptions o;
    o.fraction = 0.15;
    o.seed = 5;
    const ObserveScore s = evaluateObserve(t.model, t.testSkin, o);
    std::cout << "synthetic low, " << t.model.vertexCount() << " skin vertices, " << s.faces << " test faces, 15% random: "
              << "mean " << s.meanError << " mm (max " << s.maxError << "), mean face " << s.meanFaceMeanError << " mm (max "
              << s.meanFaceMaxError << ")\n";
    CHECK(s.measuredFraction > 0.12);
    CHECK(s.meanError < 0.5 * s.meanFaceMeanError);
}

TEST_CASE("head_model: one feature region of about 15% of the vertices gives under half the mean-face error")
{
    const test::TrainedSynth& t = test::trainedSynth();
    // Scored on every face the model was not trained on, the test and the contour roles (33):
    // the ten test faces alone put the ratio anywhere from 0.39 to 0.50 by the fixture's seed
    // (seeds 11-14, on the v13 and v14 generators alike), so they measured the draw more than the
    // model.
    const Eigen::MatrixXd contourSkin = dataset::loadShapes(t.dataset, dataset::Role::Contour, "skin");
    Eigen::MatrixXd heldOut(t.testSkin.rows() + contourSkin.rows(), t.testSkin.cols());
    heldOut << t.testSkin, contourSkin;
    ObserveOptions o;
    o.region = model::featureRegion(t.dataset.manifest, t.model, "mouth_chin", 10.0);
    const double share = double(o.region.size()) / double(t.model.vertexCount());
    const ObserveScore s = evaluateObserve(t.model, heldOut, o);
    std::cout << "synthetic low, region mouth_chin (" << 100.0 * share << "% of the vertices), " << heldOut.rows()
              << " held-out faces: mean " << s.meanError << " mm (max " << s.maxError << "), mean face " << s.meanFaceMeanError << " mm\n";
    CHECK(share > 0.10);
    CHECK(share < 0.20);
    CHECK(s.meanError < 0.5 * s.meanFaceMeanError);

    // The nose alone (about 5%) and the eyes and brows (about 12%) are reported, not
    // required to reach half.
    o.region = model::featureRegion(t.dataset.manifest, t.model, "eyes_brows", 12.0);
    const ObserveScore eyes = evaluateObserve(t.model, heldOut, o);
    std::cout << "synthetic low, region eyes_brows (" << 100.0 * double(o.region.size()) / double(t.model.vertexCount())
              << "% of the vertices): mean " << eyes.meanError << " mm, mean face " << eyes.meanFaceMeanError << " mm\n";
    CHECK(eyes.meanError < eyes.meanFaceMeanError);
    o.region = model::featureRegion(t.dataset.manifest, t.model, "nose", 10.0);
    const ObserveScore nose = evaluateObserve(t.model, heldOut, o);
    std::cout << "synthetic low, region nose (" << 100.0 * double(o.region.size()) / double(t.model.vertexCount())
              << "% of the vertices): mean " << nose.meanError << " mm, mean face " << nose.meanFaceMeanError << " mm\n";
    CHECK(nose.meanError < nose.meanFaceMeanError);
}

TEST_CASE("head_model: with correlation the unmeasured segments come closer to the truth")
{
    const test::TrainedSynth& t = test::trainedSynth();
    const Segmentation& seg = t.model.segmentation;
    const std::vector<int> region = model::featureRegion(t.dataset.manifest, t.model, "mouth_chin", 10.0);
    // Vertices held only by segments that hold no measured vertex.
    std::vector<bool> measured(static_cast<size_t>(t.model.vertexCount()), false), reached = measured;
    for (int v : region)
        measured[static_cast<size_t>(v)] = true;
    for (int s = 0; s < seg.size(); ++s) {
        const auto& members = seg.vertices[static_cast<size_t>(s)];
        if (std::any_of(members.begin(), members.end(), [&](int v) { return measured[static_cast<size_t>(v)]; }))
            for (int v : members)
                reached[static_cast<size_t>(v)] = true;
    }
    std::vector<int> unmeasured;
    for (int v = 0; v < t.model.vertexCount(); ++v)
        if (!reached[static_cast<size_t>(v)])
            unmeasured.push_back(v);
    REQUIRE(unmeasured.size() > 100);

    double with = 0.0, without = 0.0;
    for (Eigen::Index f = 0; f < t.testSkin.rows(); ++f) {
        const Eigen::VectorXd truth = t.testSkin.row(f).transpose();
        Observations obs;
        for (int v : region)
            obs.addVertex(v, truth.segment<3>(3 * v));
        ReconstructOptions off;
        off.correlation = Correlation::Off;
        const Eigen::VectorXd a = reconstruct(t.model, obs).face, b = reconstruct(t.model, obs, off).face;
        for (int v : unmeasured) {
            with += (a.segment<3>(3 * v) - truth.segment<3>(3 * v)).norm();
            without += (b.segment<3>(3 * v) - truth.segment<3>(3 * v)).norm();
        }
    }
    const double count = double(unmeasured.size()) * double(t.testSkin.rows());
    std::cout << "synthetic low, mouth_chin measured, " << unmeasured.size() << " vertices of unmeasured segments: "
              << "correlation on " << with / count << " mm, off " << without / count << " mm\n";
    CHECK(with < 0.8 * without);
}

TEST_CASE("head_model: eyeballs stay in their sockets as the face changes")
{
    const test::TrainedSynth& t = test::trainedSynth();
    const dataset::Manifest& m = t.dataset.manifest;
    REQUIRE(t.model.head.vertexCount == m.vertexCount);
    REQUIRE(t.model.head.parts.size() == 5); // two eyes, two rows of teeth, the tongue

    // Per eye: the offset from the socket ring's centroid (contour eye_socket_l/r) to the
    // eyeball's centre, in a rebuilt head against the true head. Two rebuilt heads: the true
    // skin with the parts placed by the model (the rigid following alone), and the skin
    // reconstructed from 15% of its vertices. Tolerance: 2.5 mm worst over faces and eyes
    // (an eyeball is about 24 mm across), against sockets that move by up to about 9 mm between
    // faces and eyeballs left at the mean head that miss by as much. The synthetic faces
    // place each eyeball by their own rules, not by a similarity of the lids, hence the residual.
    constexpr double kTolerance = 2.5;
    Random random(9);
    double followWorst = 0.0, worst = 0.0, frozenWorst = 0.0, ringMotion = 0.0;
    const Eigen::RowVectorXd meanFace = t.model.meanFace.transpose();
    for (Eigen::Index f = 0; f < t.testHeads.rows(); ++f) {
        Observations obs;
        for (int v = 0; v < t.model.vertexCount(); ++v)
            if (random.uniform() < 0.15)
                obs.addVertex(v, t.testSkin.row(f).segment<3>(3 * v).transpose());
        const Mesh head = model::reconstructHead(t.model, obs);
        REQUIRE(head.vertexCount() == m.vertexCount);
        REQUIRE(head.F == m.topology);
        const Eigen::RowVectorXd rebuilt = dataset::flatten(head.V);
        const Eigen::RowVectorXd followed
            = dataset::flatten(model::assembleHead(t.model.head, t.model.meanFace, t.testSkin.row(f).transpose()).V);
        for (const auto& [eye, ring] : { std::pair { "eye_left", "eye_socket_l" }, std::pair { "eye_right", "eye_socket_r" } }) {
            const std::vector<int> ball = range(*m.component(eye));
            const std::vector<int>& socket = m.contours.at(ring);
            const Eigen::RowVector3d truth = centroid(t.testHeads.row(f), ball) - centroid(t.testHeads.row(f), socket);
            const Eigen::RowVector3d got = centroid(rebuilt, ball) - centroid(rebuilt, socket);
            worst = std::max(worst, (got - truth).norm());
            followWorst = std::max(followWorst, (centroid(followed, ball) - centroid(followed, socket) - truth).norm());
            // Baseline: the eyeball left where it sits on the mean head.
            const auto part
                = std::find_if(t.model.head.parts.begin(), t.model.head.parts.end(), [&](const RigidPart& p) { return p.name == eye; });
            REQUIRE(part != t.model.head.parts.end());
            const Eigen::RowVector3d frozen = part->mean.colwise().mean() - centroid(t.testHeads.row(f), socket);
            frozenWorst = std::max(frozenWorst, (frozen - truth).norm());
            ringMotion = std::max(ringMotion, (centroid(t.testHeads.row(f), socket) - centroid(meanFace, socket)).norm());
        }
    }
    std::cout << "synthetic low, eyeball centre to socket ring, worst over " << t.testHeads.rows()
              << " faces and both eyes: " << followWorst << " mm on the true skin, " << worst << " mm on the skin rebuilt from 15%, "
              << frozenWorst << " mm left at the mean head; sockets moved up to " << ringMotion << " mm\n";
    CHECK(followWorst < kTolerance);
    CHECK(worst < kTolerance);
    CHECK(frozenWorst > 2.0 * kTolerance);
    CHECK(ringMotion > 2.0 * kTolerance);
}

TEST_CASE("head_model: the model file keeps the whole head")
{
    const test::TrainedSynth& t = test::trainedSynth();
    saveFaceModel(t.model, t.dir / "faces.model");
    const FaceModel back = loadFaceModel(t.dir / "faces.model");
    Observations obs;
    for (int v = 0; v < t.model.vertexCount(); v += 7)
        obs.addVertex(v, t.testSkin.row(0).segment<3>(3 * v).transpose());
    const Mesh a = model::reconstructHead(t.model, obs), b = model::reconstructHead(back, obs);
    CHECK(a.V == b.V);
    CHECK(a.F == b.F);
    model::requireModelFits(back, t.dataset.manifest, "test");
}

TEST_CASE("head_model: datasets without a nose tip or train faces are refused")
{
    test::TempDir dir;
    dataset::SynthOptions s;
    s.identities = 3;
    dataset::writeSynthDataset(dir / "few", s);
    REQUIRE_THROWS_WITH(model::trainHeadModel(dataset::openDataset(dir / "few")), Catch::Contains("need at least 4"));
    dataset::Dataset ds = dataset::openDataset(dir / "few");
    ds.manifest.landmarks.erase("prn");
    REQUIRE_THROWS_WITH(model::trainHeadModel(ds), Catch::Contains("no landmark \"prn\""));
}

TEST_CASE("head_model: an ICT-FaceKit import observed at 15% at random or at one region gives under half the mean-face error")
{
    const std::filesystem::path ict = "/work/shared/datasets/ict-facekit";
    if (!std::filesystem::exists(ict / "FaceXModel" / "generic_neutral_mesh.obj")) {
        WARN("skipped: no ICT-FaceKit at " << ict.string());
        return;
    }
    test::TempDir dir;
    dataset::IctOptions io;
    io.identities = 250; // 182 train, 48 contour, 20 test, as the thesis split them
    io.vertices = 1500;
    io.eyes = true;
    dataset::writeIctDataset(ict, dir / "ict", io);
    const dataset::Dataset ds = dataset::openDataset(dir / "ict");
    // The default clean-up and correlation dimensions: ICT's ~100 identity modes move the whole
    // face, and the joint model needs room for them.
    model::HeadModelOptions options = test::smallHeadOptions();
    options.face.cleanUpDim = stats::FaceModelOptions {}.cleanUpDim;
    options.face.correlationLatentDim = stats::FaceModelOptions {}.correlationLatentDim;
    const FaceModel model = model::trainHeadModel(ds, options);
    const Eigen::MatrixXd test = dataset::loadShapes(ds, dataset::Role::Test, "skin");
    REQUIRE(test.rows() >= 5);

    ObserveOptions o;
    o.seed = 3;
    const ObserveScore random = evaluateObserve(model, test, o);
    o.region = model::featureRegion(ds.manifest, model, "mouth_chin", 10.0);
    const double share = double(o.region.size()) / double(model.vertexCount());
    const ObserveScore region = evaluateObserve(model, test, o);
    o.reconstruct.correlation = Correlation::Thesis;
    const ObserveScore thesis = evaluateObserve(model, test, o);
    o.reconstruct.correlation = Correlation::Off;
    const ObserveScore uncorrelated = evaluateObserve(model, test, o);
    std::cout << "ICT import, " << model.vertexCount() << " skin vertices, " << random.faces << " test faces: 15% random "
              << random.meanError << " mm (max " << random.maxError << "); mouth_chin (" << 100.0 * share << "%) " << region.meanError
              << " mm, thesis correlation " << thesis.meanError << " mm, without correlation " << uncorrelated.meanError
              << " mm; mean face " << random.meanFaceMeanError << " mm\n";
    CHECK(random.meanError < 0.5 * random.meanFaceMeanError);
    CHECK(share < 0.2);
    CHECK(region.meanError < 0.5 * region.meanFaceMeanError);
    // The thesis' route (4.2.5) does not reach half on ICT (about 0.7 of the mean face): its
    // identity modes each move the whole face, and a segment seen at a few border vertices
    // passes on a poorly determined latent. Both routes beat no correlation.
    CHECK(region.meanError < thesis.meanError);
    CHECK(thesis.meanError < uncorrelated.meanError);
    // The whole head comes back, eyeballs included.
    Observations obs;
    for (int v : o.region)
        obs.addVertex(v, test.row(0).segment<3>(3 * v).transpose());
    CHECK(model::reconstructHead(model, obs).vertexCount() == ds.manifest.vertexCount);
}

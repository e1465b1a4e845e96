// Tests of stats/face_model on synthetic faces: a grid "face" with a nose bump, two face types
// (small and large nose) and smooth global shape modes, in millimetres. Held-out faces are
// reconstructed from a fraction of their vertices and from one region only.
#include "stats/face_model.h"

#include "core/error.h"
#include "core/random.h"
#include "stats/model_file.h"
#include "synthetic_faces.h"
#include "test_common.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace facesketch;
using namespace facesketch::stats;
using namespace facesketch::test;

namespace {

FaceModelOptions smallOptions()
{
    FaceModelOptions options;
    options.segmentation.clusters = 6;
    options.segmentation.minVertices = 30;
    options.segmentation.maxVertices = 200;
    options.components = { 1, 2 };
    options.folds = 3;
    options.mppca.restarts = 2;
    options.latentDim = 6;
    options.cleanUpDim = 10;
    options.correlationLatentDim = 10;
    return options;
}

// Mean over the listed vertices (all if empty) of |a_v - b_v|, mm.
double meanVertexError(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const std::vector<int>& only = {})
{
    double sum = 0.0;
    int count = 0;
    for (Eigen::Index v = 0; v < a.size() / 3; ++v)
        if (only.empty() || std::find(only.begin(), only.end(), v) != only.end()) {
            sum += (a.segment<3>(3 * v) - b.segment<3>(3 * v)).norm();
            ++count;
        }
    return sum / count;
}

struct Trained {
    Eigen::MatrixXd test;
    FaceModel model;
};

const Trained& trained()
{
    static const Trained t = [] {
        Random random(41);
        Trained out;
        const Eigen::MatrixXd train = syntheticFaces(random, 100);
        out.test = syntheticFaces(random, 10);
        out.model = trainFaceModel(train, gridTriangles(), kNoseTip, smallOptions());
        return out;
    }();
    return t;
}

} // namespace

TEST_CASE("face_model: 15% of the vertices give under half the mean-face error")
{
    const Trained& t = trained();
    REQUIRE(t.model.segmentation.size() >= 3);
    // The summary `facesketch train` prints: a header, one line per segment, the correlation
    // and the joint model.
    const std::string table = describe(t.model);
    CHECK(std::count(table.begin(), table.end(), '\n') == t.model.segmentation.size() + 3);
    CHECK(table.find("joint model: 1 components over " + std::to_string(t.model.meanFace.size()) + " coordinates") != std::string::npos);
    Random random(42);
    double modelError = 0.0, meanError = 0.0;
    for (Eigen::Index f = 0; f < t.test.rows(); ++f) {
        const Eigen::VectorXd truth = t.test.row(f).transpose();
        Observations obs;
        for (int v = 0; v < kSide * kSide; ++v)
            if (random.uniform() < 0.15)
                obs.addVertex(v, truth.segment<3>(3 * v));
        const Reconstruction r = reconstruct(t.model, obs);
        REQUIRE(r.winners.size() == static_cast<size_t>(t.model.segmentation.size()));
        modelError += meanVertexError(r.face, truth) / t.test.rows();
        meanError += meanVertexError(t.model.meanFace, truth) / t.test.rows();
    }
    INFO("mean per-vertex error: model " << modelError << " mm, mean face " << meanError << " mm");
    CHECK(modelError < 0.5 * meanError);
}

TEST_CASE("face_model: correlation brings unmeasured segments closer to the truth")
{
    const Trained& t = trained();
    const Segmentation& seg = t.model.segmentation;
    // Measure the vertices that only the nose tip's segment holds (one feature region);
    // score the vertices that no measured segment holds.
    std::vector<int> holders(static_cast<size_t>(kSide * kSide), 0);
    for (int s = 0; s < seg.size(); ++s)
        for (int v : seg.vertices[static_cast<size_t>(s)])
            ++holders[static_cast<size_t>(v)];
    const int nose = seg.core(kNoseTip);
    std::vector<int> measured;
    for (int v = 0; v < kSide * kSide; ++v)
        if (seg.core(v) == nose && holders[static_cast<size_t>(v)] == 1)
            measured.push_back(v);
    REQUIRE(measured.size() >= 10);

    double joint = 0.0, thesis = 0.0, without = 0.0, meanError = 0.0;
    size_t scored = 0;
    for (Eigen::Index f = 0; f < t.test.rows(); ++f) {
        const Eigen::VectorXd truth = t.test.row(f).transpose();
        Observations obs;
        for (int v : measured)
            obs.addVertex(v, truth.segment<3>(3 * v));
        ReconstructOptions onJoint, onThesis, off;
        onThesis.correlation = Correlation::Thesis;
        off.correlation = Correlation::Off;
        const Reconstruction a = reconstruct(t.model, obs, onJoint), b = reconstruct(t.model, obs, onThesis),
                             c = reconstruct(t.model, obs, off);
        REQUIRE(b.winners == c.winners);
        REQUIRE(a.jointWinner == 0);
        REQUIRE(c.jointWinner == -1);
        std::vector<int> unmeasured;
        for (int v = 0; v < kSide * kSide; ++v) {
            bool held = false;
            for (int s = 0; s < seg.size(); ++s)
                if (c.winners[static_cast<size_t>(s)] >= 0)
                    held = held
                        || std::binary_search(seg.vertices[static_cast<size_t>(s)].begin(), seg.vertices[static_cast<size_t>(s)].end(), v);
            if (!held)
                unmeasured.push_back(v);
        }
        REQUIRE(unmeasured.size() > 100);
        scored = unmeasured.size();
        joint += meanVertexError(a.face, truth, unmeasured) / t.test.rows();
        thesis += meanVertexError(b.face, truth, unmeasured) / t.test.rows();
        without += meanVertexError(c.face, truth, unmeasured) / t.test.rows();
        meanError += meanVertexError(t.model.meanFace, truth, unmeasured) / t.test.rows();
    }
    INFO(measured.size() << " vertices measured, " << scored << " scored: correlation joint " << joint << " mm, thesis " << thesis
                         << " mm, off " << without << " mm, mean face " << meanError << " mm");
    CHECK(joint < 0.75 * without);
    CHECK(thesis < 0.75 * without);
}

TEST_CASE("face_model: the joint model is the correlation mixture composed with the segment decoders")
{
    const Trained& t = trained();
    const FaceModel& m = t.model;
    REQUIRE(m.joint.size() == m.correlation.size());
    Random random(7);
    for (Eigen::Index k = 0; k < m.joint.size(); ++k) {
        const Ppca& c = m.correlation.components[static_cast<size_t>(k)];
        const Ppca& j = m.joint.components[static_cast<size_t>(k)];
        REQUIRE(j.dim() == m.meanFace.size());
        REQUIRE(j.latentDim() == c.latentDim());
        // Independently: a latent u gives the segment latents m + A u, each segment decoded by
        // eq. 4.20 (fromLatent) and the segments blended.
        const Eigen::VectorXd u = random.normalMatrix(c.latentDim(), 1);
        const Eigen::VectorXd latents = c.mean + c.W * u;
        std::vector<Eigen::VectorXd> parts;
        double noise = 0.0, coordinates = 0.0;
        Eigen::Index offset = 0;
        for (const SegmentModel& sm : m.segments) {
            const Ppca& p = sm.cleanUp;
            parts.push_back(fromLatent(p, latents.segment(offset, p.latentDim()).transpose()).transpose());
            // The covariance sigma_s^2 I + tau^2 D_s D_s^T with D_s the decoder x -> fromLatent(x) - mu,
            // here taken column by column from fromLatent, averaged over its diagonal.
            Eigen::MatrixXd D(p.dim(), p.latentDim());
            for (Eigen::Index i = 0; i < p.latentDim(); ++i)
                D.col(i) = fromLatent(p, Eigen::RowVectorXd::Unit(p.latentDim(), i)).transpose() - p.mean;
            const Eigen::MatrixXd cov = p.sigma2 * Eigen::MatrixXd::Identity(p.dim(), p.dim()) + c.sigma2 * D * D.transpose();
            noise += cov.trace();
            coordinates += static_cast<double>(p.dim());
            offset += p.latentDim();
        }
        const Eigen::VectorXd expected = blendSegments(m.segmentation, parts);
        const Eigen::VectorXd got = j.mean + j.W * u;
        CHECK((got - expected).norm() <= 1e-9 * expected.norm());
        CHECK(std::abs(j.sigma2 - noise / coordinates) <= 1e-12 * j.sigma2);
    }
}

TEST_CASE("face_model: with joint correlation one region informs every segment")
{
    // Measure only the nose tip's segment core; under the thesis' route the other measured
    // segments (those holding a few border vertices) are inferred from those few vertices
    // alone, under the joint route from all of them.
    const Trained& t = trained();
    const Segmentation& seg = t.model.segmentation;
    const int nose = seg.core(kNoseTip);
    double joint = 0.0, thesis = 0.0, meanError = 0.0;
    for (Eigen::Index f = 0; f < t.test.rows(); ++f) {
        const Eigen::VectorXd truth = t.test.row(f).transpose();
        Observations obs;
        for (int v = 0; v < kSide * kSide; ++v)
            if (seg.core(v) == nose)
                obs.addVertex(v, truth.segment<3>(3 * v));
        ReconstructOptions onThesis;
        onThesis.correlation = Correlation::Thesis;
        joint += meanVertexError(reconstruct(t.model, obs).face, truth) / t.test.rows();
        thesis += meanVertexError(reconstruct(t.model, obs, onThesis).face, truth) / t.test.rows();
        meanError += meanVertexError(t.model.meanFace, truth) / t.test.rows();
    }
    INFO("whole face from the nose segment: joint " << joint << " mm, thesis " << thesis << " mm, mean face " << meanError << " mm");
    CHECK(joint < thesis);
    CHECK(joint < 0.5 * meanError);
    CHECK(parseCorrelation("thesis") == Correlation::Thesis);
    REQUIRE_THROWS_WITH(parseCorrelation("both"), Catch::Contains("'both'"));
}

TEST_CASE("face_model: measured vertices are kept without clean-up, and bad input is rejected")
{
    const Trained& t = trained();
    const Eigen::VectorXd truth = t.test.row(0).transpose();
    Observations obs;
    obs.addVertex(kNoseTip, truth.segment<3>(3 * kNoseTip));
    ReconstructOptions raw;
    raw.cleanUp = false;
    const Reconstruction r = reconstruct(t.model, obs, raw);
    // The nose tip is in the core of one segment; overlapping segments that hold it see the
    // same measurement, so the blend returns it exactly.
    CHECK((r.face.segment<3>(3 * kNoseTip) - truth.segment<3>(3 * kNoseTip)).norm() < 1e-9);
    Observations outside;
    outside.addVertex(kSide * kSide, Eigen::Vector3d::Zero());
    REQUIRE_THROWS_AS(reconstruct(t.model, outside), Error);
    Eigen::MatrixXd bad = t.test;
    bad(2, 5) = std::nan("");
    REQUIRE_THROWS_WITH(trainFaceModel(bad, gridTriangles(), kNoseTip, smallOptions()), Catch::Contains("faces(2, 5)"));
}

TEST_CASE("face_model: reconstructAt is the joint conditional mean at the asked vertices")
{
    const Trained& t = trained();
    const Eigen::VectorXd truth = t.test.row(1).transpose();
    const Eigen::Matrix<double, 2, 3> front = (Eigen::Matrix<double, 2, 3>() << 1, 0, 0, 0, 1, 0).finished();
    Observations obs;
    std::vector<int> at;
    for (int v = 0; v < kSide * kSide; v += 7) {
        if (v % 2 == 0)
            obs.addVertex(v, truth.segment<3>(3 * v), 0.5);
        else
            obs.addProjectedVertex(v, front, front * truth.segment<3>(3 * v));
        at.push_back(v);
    }
    at.push_back(kNoseTip); // one vertex nobody measured
    // Without the clean-up, the blend of segments cut from one joint face is that face.
    ReconstructOptions raw;
    raw.cleanUp = false;
    const Eigen::VectorXd whole = reconstruct(t.model, obs, raw).face;
    const Eigen::VectorXd some = reconstructAt(t.model, obs, at, raw);
    REQUIRE(some.size() == 3 * static_cast<Eigen::Index>(at.size()));
    for (size_t i = 0; i < at.size(); ++i)
        CHECK((some.segment<3>(3 * static_cast<Eigen::Index>(i)) - whole.segment<3>(3 * at[i])).norm() < 1e-9);
    // Other correlations: reconstruct's face, picked at the vertices.
    ReconstructOptions thesis;
    thesis.correlation = Correlation::Thesis;
    const Eigen::VectorXd full = reconstruct(t.model, obs, thesis).face;
    const Eigen::VectorXd picked = reconstructAt(t.model, obs, at, thesis);
    for (size_t i = 0; i < at.size(); ++i)
        CHECK(picked.segment<3>(3 * static_cast<Eigen::Index>(i)) == full.segment<3>(3 * at[i]));
    REQUIRE_THROWS_WITH(reconstructAt(t.model, obs, { kSide * kSide }), Catch::Contains("vertex " + std::to_string(kSide * kSide)));
}

TEST_CASE("face_model: each segment's clean-up keeps the dimensions that hold cleanUpVariance of its variance, at most cleanUpDim")
{
    Random random(41);
    const Eigen::MatrixXd train = syntheticFaces(random, 100); // trained()'s training faces
    // These faces vary along a few smooth modes plus noise: a segment holds 99% of its variance
    // in 6 to 8 directions and 99.9% only in 62 to 79, so at 0.99 the rule bites under the
    // cap of 10 (smallOptions) and at 1 every segment keeps the cap.
    FaceModelOptions options = smallOptions();
    options.cleanUpVariance = 0.99;
    const FaceModel byVariance = trainFaceModel(train, gridTriangles(), kNoseTip, options);
    options.cleanUpVariance = 1.0;
    const FaceModel capped = trainFaceModel(train, gridTriangles(), kNoseTip, options);
    REQUIRE(capped.segmentation.size() == byVariance.segmentation.size());
    int below = 0;
    for (int s = 0; s < byVariance.segmentation.size(); ++s) {
        INFO("segment " << s);
        const Eigen::MatrixXd Xs = train(Eigen::all, segmentCoordinates(byVariance.segmentation, s));
        const int q = byVariance.segments[static_cast<size_t>(s)].cleanUp.latentDim();
        CHECK(capped.segments[static_cast<size_t>(s)].cleanUp.latentDim() == 10);
        CHECK(q == std::clamp(dimensionHolding(Xs, 0.99), 1, 10));
        below += q < 10;
    }
    CHECK(below == byVariance.segmentation.size());
    for (double bad : { 0.0, 1.5 }) {
        options.cleanUpVariance = bad;
        REQUIRE_THROWS_WITH(trainFaceModel(train, gridTriangles(), kNoseTip, options), Catch::Contains("cleanUpVariance"));
    }
}

TEST_CASE("face_model: the segments fitted on several threads give the model one thread gives, byte for byte")
{
    Random random(41);
    const Eigen::MatrixXd train = syntheticFaces(random, 100); // trained()'s training faces
    const TempDir dir;
    auto savedBytes = [&](int threads) {
        FaceModelOptions options = smallOptions();
        options.threads = threads;
        const FaceModel model = trainFaceModel(train, gridTriangles(), kNoseTip, options);
        REQUIRE(model.segmentation.size() >= 3); // enough segments for the threads to share
        const std::filesystem::path path = dir / ("threads-" + std::to_string(threads) + ".model");
        saveFaceModel(model, path);
        return test::readBytes(path);
    };
    const std::string one = savedBytes(1);
    REQUIRE(!one.empty());
    REQUIRE(savedBytes(3) == one);
    REQUIRE(savedBytes(0) == one);
}

// Tests of stats/conditional: conditional means and marginal likelihoods against the dense
// textbook formulas, thesis eq. 4.21 in its precision-matrix form, what happens to observed
// vertices, choosing the component, and bad input.
#include "stats/conditional.h"

#include "core/error.h"
#include "synthetic.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <limits>

using namespace facesketch;
using namespace facesketch::stats;
using namespace facesketch::test;

namespace {

Eigen::Matrix<double, 2, 3> randomView(Random& random)
{
    const Eigen::Vector3d axis = random.normalMatrix(3, 1).normalized();
    const Eigen::Matrix3d R = Eigen::AngleAxisd(2.0 * random.uniform() * 3.14159, axis).toRotationMatrix();
    return R.topRows<2>();
}

// Observes each of `vertices` vertices of t in full, in 2D, not at all, or one coordinate.
Observations randomObservations(Random& random, const Eigen::VectorXd& t, Eigen::Index vertices)
{
    Observations obs;
    for (Eigen::Index v = 0; v < vertices; ++v) {
        const Eigen::Vector3d p = t.segment<3>(3 * v);
        switch (random.index(4)) {
        case 0:
            obs.addVertex(v, p);
            break;
        case 1: {
            const Eigen::Matrix<double, 2, 3> P = randomView(random);
            obs.addProjectedVertex(v, P, P * p + 0.1 * random.normalMatrix(2, 1));
            break;
        }
        case 2:
            obs.addCoordinate(3 * v + random.index(3), p(0) + 0.2);
            break;
        default:
            break;
        }
    }
    return obs;
}

} // namespace

TEST_CASE("conditional: means and log-likelihoods match the dense formulas")
{
    Random random(31);
    for (int trial = 0; trial < 30; ++trial) {
        const Eigen::Index vertices = 7 + random.index(7); // d = 21 .. 39
        const Eigen::Index d = 3 * vertices;
        const int q = 1 + static_cast<int>(random.index(6));
        const Ppca model = randomPpca(random, d, q, 3.0, 1.0, 0.05 + random.uniform());
        const Eigen::VectorXd t = model.mean + 2.0 * random.normalMatrix(d, 1);
        const Observations obs = randomObservations(random, t, vertices);

        const ComponentPosterior post = condition(model, obs);
        const Eigen::VectorXd mean = conditionalMean(model, obs, post);

        // Dense: y ~ N(P mu, P C P^T), E[t | y] = mu + C P^T (P C P^T)^{-1} (y - P mu).
        const Eigen::MatrixXd C = denseCovariance(model);
        const Eigen::MatrixXd P = obs.denseP(d);
        const Eigen::VectorXd y = obs.values();
        INFO("trial " << trial << ": d = " << d << ", q = " << q << ", o = " << obs.size());
        if (obs.size() == 0) {
            CHECK(post.logLikelihood == 0.0);
            CHECK(relativeDifference(mean, model.mean) < 1e-12);
            continue;
        }
        const Eigen::MatrixXd Cyy = P * C * P.transpose();
        const Eigen::VectorXd expected = model.mean + C * P.transpose() * Cyy.llt().solve(y - P * model.mean);
        CHECK(relativeDifference(mean, expected) < 1e-9);
        CHECK(relativeDifference(post.logLikelihood, denseLogDensity(y, P * model.mean, Cyy)) < 1e-9);
        // The latent posterior mean: E[x | y] = W^T P^T (P C P^T)^{-1} (y - P mu).
        const Eigen::VectorXd z = model.W.transpose() * P.transpose() * Cyy.llt().solve(y - P * model.mean);
        CHECK(relativeDifference(post.latent, z) < 1e-9);
    }
}

TEST_CASE("conditional: the missing block follows thesis eq. 4.21 in precision form")
{
    Random random(32);
    const Eigen::Index d = 30;
    const Ppca model = randomPpca(random, d, 4, 2.0, 1.0, 0.4);
    const Eigen::VectorXd t = model.mean + random.normalMatrix(d, 1);
    // Vertices 0, 3, 4 and 8 observed; the rest missing.
    const std::vector<Eigen::Index> seen = { 0, 3, 4, 8 };
    Observations obs;
    std::vector<Eigen::Index> o, m;
    for (Eigen::Index v = 0; v < d / 3; ++v) {
        const bool isSeen = std::find(seen.begin(), seen.end(), v) != seen.end();
        if (isSeen)
            obs.addVertex(v, t.segment<3>(3 * v));
        for (int c = 0; c < 3; ++c)
            (isSeen ? o : m).push_back(3 * v + c);
    }
    const Eigen::VectorXd mean = conditionalMean(model, obs, condition(model, obs));

    // t_m = mu_m - Lambda_mm^{-1} Lambda_mo (t_o - mu_o) with Lambda = C^{-1}.
    const Eigen::MatrixXd Lambda = denseCovariance(model).inverse();
    const Eigen::MatrixXd Lmm = Lambda(m, m);
    const Eigen::MatrixXd Lmo = Lambda(m, o);
    const Eigen::VectorXd expected = model.mean(m) - Lmm.llt().solve(Lmo * (t(o) - model.mean(o)));
    CHECK(relativeDifference(Eigen::VectorXd(mean(m)), expected) < 1e-9);
    // The observed block comes back unchanged.
    CHECK(relativeDifference(Eigen::VectorXd(mean(o)), Eigen::VectorXd(t(o))) < 1e-14);
}

TEST_CASE("conditional: a noise-free whole measurement comes back bit for bit, a noisy one is pulled")
{
    // Measurements far from the model's mean and of the other sign: a + (y - a) rounds there
    // (the pose completion test "a pose completed from all its FPs is itself" met one such
    // coordinate on the v20 faces).
    Random random(41);
    const Eigen::Index d = 30;
    const Ppca model = randomPpca(random, d, 4, 2.0, 1.0, 0.4);
    Observations obs;
    Eigen::VectorXd y(7);
    for (Eigen::Index v = 0; v < 2; ++v) {
        const Eigen::Vector3d p = -model.mean.segment<3>(3 * v) * 3.7 + Eigen::Vector3d(1e-7, -0.1 / 3, 1.0 / 3);
        obs.addVertex(v, p);
        y.segment<3>(3 * v) = p;
    }
    y(6) = -std::abs(model.mean(20)) * 5.3 - 0.1 / 7;
    obs.addCoordinate(20, y(6));
    obs.addVertex(5, Eigen::Vector3d(0.3, -0.7, 1.1), 0.5);
    const Eigen::VectorXd t = conditionalMean(model, obs, condition(model, obs));
    for (Eigen::Index i = 0; i < 6; ++i)
        CHECK(t(i) == y(i));
    CHECK(t(20) == y(6));
    // The noisy vertex is pulled towards its measurement, not pinned to it.
    CHECK((t.segment<3>(15) - Eigen::Vector3d(0.3, -0.7, 1.1)).norm() > 1e-6);
}

TEST_CASE("conditional: a vertex seen in 2D keeps its image and gets its depth from the model")
{
    Random random(33);
    const Ppca model = randomPpca(random, 24, 3, 2.0, 1.0, 0.3);
    const Eigen::Matrix<double, 2, 3> P = randomView(random);
    const Eigen::Vector2d image(1.0, -2.0);
    Observations obs;
    obs.addProjectedVertex(5, P, image);
    obs.addVertex(1, Eigen::Vector3d(0.5, 0.25, -1.0));
    const Eigen::VectorXd mean = conditionalMean(model, obs, condition(model, obs));
    CHECK((P * mean.segment<3>(15) - image).norm() < 1e-12);
    CHECK((mean.segment<3>(3) - Eigen::Vector3d(0.5, 0.25, -1.0)).norm() < 1e-12);
}

TEST_CASE("conditional: a vertex measured along one direction keeps that coordinate, the model fills the rest")
{
    Random random(35);
    const Ppca model = randomPpca(random, 24, 3, 2.0, 1.0, 0.3);
    const Eigen::Vector3d d = random.normalMatrix(3, 1).normalized();
    Observations obs;
    obs.addVertexAlong(4, d, 1.5);
    obs.addVertex(1, Eigen::Vector3d(0.5, 0.25, -1.0));
    REQUIRE(obs.size() == 4);
    // The fast P A agrees with the dense P.
    const Eigen::MatrixXd A = random.normalMatrix(24, 5);
    CHECK((obs.apply(A) - obs.denseP(24) * A).norm() < 1e-12);
    const Eigen::VectorXd mean = conditionalMean(model, obs, condition(model, obs));
    CHECK(std::abs(d.dot(mean.segment<3>(12)) - 1.5) < 1e-12);
    // The other two directions are the model's: not those of the vertex moved along d only.
    const Eigen::VectorXd unmeasured = conditionalMean(model, Observations {}, condition(model, Observations {}));
    CHECK(((mean.segment<3>(12) - unmeasured.segment<3>(12)) - d * d.dot(mean.segment<3>(12) - unmeasured.segment<3>(12))).norm() > 1e-6);

    Observations bad;
    REQUIRE_THROWS_WITH(bad.addVertexAlong(2, 2 * d, 1.0), Catch::Contains("length"));
    REQUIRE_THROWS_WITH(bad.addVertexAlong(2, d, std::numeric_limits<double>::infinity()), Catch::Contains("not finite"));
    REQUIRE(bad.empty());
}

TEST_CASE("conditional: the winner is the component that drew the face")
{
    Random random(34);
    Mppca mixture;
    for (int k = 0; k < 3; ++k)
        mixture.components.push_back(randomPpca(random, 60, 3, 3.0, 1.0, 0.2));
    mixture.priors = Eigen::Vector3d(0.5, 0.3, 0.2);
    for (int k = 0; k < 3; ++k) {
        const Ppca& c = mixture.components[static_cast<size_t>(k)];
        const Eigen::VectorXd t = c.mean + c.W * random.normalMatrix(3, 1) + 0.45 * random.normalMatrix(60, 1);
        Observations obs;
        for (Eigen::Index v = 0; v < 20; v += 4)
            obs.addVertex(v, t.segment<3>(3 * v));
        const Inference result = infer(mixture, obs);
        CHECK(result.winner == k);
        CHECK(std::abs(result.posterior.sum() - 1.0) < 1e-12);
        CHECK(result.posterior(k) > 0.99);
        // Scores are eq. 4.16: the dense marginal density of the observed block plus log prior.
        const Eigen::MatrixXd P = obs.denseP(60);
        for (int j = 0; j < 3; ++j) {
            const Ppca& cj = mixture.components[static_cast<size_t>(j)];
            const double dense
                = denseLogDensity(obs.values(), P * cj.mean, P * denseCovariance(cj) * P.transpose()) + std::log(mixture.priors(j));
            CHECK(relativeDifference(result.components[static_cast<size_t>(j)].score(), dense) < 1e-9);
        }
        // The reconstruction is the winner's conditional mean, closer to the truth than its mean.
        CHECK((result.reconstruction - t).norm() < (c.mean - t).norm());
    }
}

TEST_CASE("conditional: rejects overlapping, out-of-range and non-finite measurements")
{
    Random random(35);
    const Ppca model = randomPpca(random, 12, 2, 1.0, 1.0, 0.5);
    Observations twice;
    twice.addVertex(1, Eigen::Vector3d::Zero());
    twice.addCoordinate(4, 1.0);
    REQUIRE_THROWS_WITH(condition(model, twice), Catch::Contains("coordinate 4"));
    Observations outside;
    outside.addVertex(4, Eigen::Vector3d::Zero());
    REQUIRE_THROWS_AS(condition(model, outside), Error);

    Observations obs;
    REQUIRE_THROWS_WITH(
        obs.addVertex(2, Eigen::Vector3d(0.0, std::numeric_limits<double>::quiet_NaN(), 0.0)), Catch::Contains("xyz(1, 0)"));
    Eigen::Matrix<double, 2, 3> skew;
    skew << 1, 0, 0, 1, 1, 0;
    REQUIRE_THROWS_WITH(obs.addProjectedVertex(0, skew, Eigen::Vector2d::Zero()), Catch::Contains("orthonormal"));
    REQUIRE_THROWS_AS(obs.addCoordinate(-1, 0.0), Error);
}

TEST_CASE("conditional: noisy measurements match the dense Gaussian formulas and pull rather than pin")
{
    Random random(41);
    const Ppca model = randomPpca(random, 24, 3, 2.0, 1.0, 0.3);
    const Eigen::VectorXd t = model.mean + model.W * random.normalMatrix(3, 1);
    const Eigen::Matrix<double, 2, 3> P = randomView(random);
    const Eigen::Vector3d d = random.normalMatrix(3, 1).normalized();
    Observations obs;
    obs.addVertex(1, t.segment<3>(3) + Eigen::Vector3d(0.3, -0.2, 0.1), 0.5);
    obs.addProjectedVertex(3, P, P * t.segment<3>(9) + Eigen::Vector2d(0.4, 0.1), Eigen::Vector2d(0.0, 2.0));
    obs.addVertexAlong(5, d, d.dot(t.segment<3>(15)) - 0.3, 1.5);
    obs.addVertex(6, t.segment<3>(18));
    REQUIRE(obs.noisy());
    const Eigen::VectorXd n = obs.noiseVariances();
    REQUIRE(n.size() == 9);
    CHECK(n[3] == 0.0);
    CHECK(n[4] == 2.0);

    // Dense: t ~ N(mu, C), y = P t + e, e ~ N(0, diag(n)).
    const Eigen::MatrixXd C = model.sigma2 * Eigen::MatrixXd::Identity(24, 24) + model.W * model.W.transpose();
    const Eigen::MatrixXd Pd = obs.denseP(24);
    const Eigen::MatrixXd S = Pd * C * Pd.transpose() + Eigen::MatrixXd(n.asDiagonal());
    const Eigen::VectorXd r = obs.values() - Pd * model.mean;
    const Eigen::VectorXd expected = model.mean + C * Pd.transpose() * S.ldlt().solve(r);
    const double logLikelihood = -0.5 * (9 * std::log(2.0 * 3.14159265358979323846) + std::log(S.determinant()) + r.dot(S.ldlt().solve(r)));
    const ComponentPosterior post = condition(model, obs);
    CHECK((conditionalMean(model, obs, post) - expected).norm() < 1e-9);
    CHECK(std::abs(post.logLikelihood - logLikelihood) < 1e-8);

    // A noisy measurement is not met exactly; a noiseless one still is, and vanishing noise
    // tends to the pinned result.
    const Eigen::VectorXd mean = conditionalMean(model, obs, post);
    CHECK((mean.segment<3>(3) - (t.segment<3>(3) + Eigen::Vector3d(0.3, -0.2, 0.1))).norm() > 1e-3);
    CHECK((mean.segment<3>(18) - t.segment<3>(18)).norm() < 1e-9);
    Observations pinned, almost;
    pinned.addVertex(1, t.segment<3>(3));
    pinned.addVertexAlong(5, d, 0.7);
    almost.addVertex(1, t.segment<3>(3), 1e-10);
    almost.addVertexAlong(5, d, 0.7, 1e-10);
    CHECK((conditionalMean(model, pinned, condition(model, pinned)) - conditionalMean(model, almost, condition(model, almost))).norm()
        < 1e-6);

    Observations bad;
    REQUIRE_THROWS_WITH(bad.addVertex(2, Eigen::Vector3d::Zero(), -1.0), Catch::Contains("noise variance -1"));
    REQUIRE_THROWS_WITH(bad.addVertexAlong(2, d, 0.0, std::numeric_limits<double>::quiet_NaN()), Catch::Contains("noise variance"));
    REQUIRE(bad.empty());
}

TEST_CASE("conditional: rows of any orthonormal frame measure a vertex, each with its own noise")
{
    Random random(43);
    const Ppca model = randomPpca(random, 24, 3, 2.0, 1.0, 0.3);
    const Eigen::VectorXd t = model.mean + model.W * random.normalMatrix(3, 1);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::Vector3d p = t.segment<3>(6) + Eigen::Vector3d(0.2, -0.1, 0.3);

    // Three rows of noise 0 are the vertex itself; two are its image in the view of R.
    Observations rows, vertex;
    rows.addVertexRows(2, R, 3, R * p, Eigen::Vector3d::Zero());
    vertex.addVertex(2, p);
    CHECK((conditionalMean(model, rows, condition(model, rows)) - conditionalMean(model, vertex, condition(model, vertex))).norm() < 1e-9);
    Observations two, image;
    two.addVertexRows(2, R, 2, R * p, Eigen::Vector3d(0.5, 2.0, 0.0));
    image.addProjectedVertex(2, R.topRows<2>(), R.topRows<2>() * p, Eigen::Vector2d(0.5, 2.0));
    REQUIRE(two.size() == 2);
    CHECK(two.noiseVariances() == image.noiseVariances());
    CHECK((conditionalMean(model, two, condition(model, two)) - conditionalMean(model, image, condition(model, image))).norm() < 1e-12);

    // Each row's noise counts: the dense Gaussian formulas.
    Observations noisy;
    noisy.addVertexRows(2, R, 3, R * p, Eigen::Vector3d(0.1, 1.0, 4.0));
    const Eigen::MatrixXd C = model.sigma2 * Eigen::MatrixXd::Identity(24, 24) + model.W * model.W.transpose();
    const Eigen::MatrixXd Pd = noisy.denseP(24);
    const Eigen::MatrixXd S = Pd * C * Pd.transpose() + Eigen::MatrixXd(noisy.noiseVariances().asDiagonal());
    const Eigen::VectorXd expected = model.mean + C * Pd.transpose() * S.ldlt().solve(noisy.values() - Pd * model.mean);
    CHECK((conditionalMean(model, noisy, condition(model, noisy)) - expected).norm() < 1e-9);

    Observations bad;
    Eigen::Matrix3d skew = R;
    skew(1, 0) += 0.1;
    REQUIRE_THROWS_WITH(bad.addVertexRows(2, skew, 2, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), Catch::Contains("orthonormal"));
    REQUIRE_THROWS_WITH(bad.addVertexRows(2, R, 4, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), Catch::Contains("4 rows"));
    REQUIRE_THROWS_WITH(bad.addVertexRows(2, R, 1, Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 0), Eigen::Vector3d::Zero()),
        Catch::Contains("values"));
    REQUIRE_THROWS_WITH(
        bad.addVertexRows(2, R, 2, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, -2, 0)), Catch::Contains("noise variance -2"));
    REQUIRE(bad.empty());
}

// Tests of stats/kmeans: the objective's history and final value against a direct
// computation, optimality of the final assignment, the seeding rule, recovery of clusters.
#include "stats/kmeans.h"

#include "core/error.h"
#include "core/random.h"

#include <catch2/catch.hpp>
#include <limits>
#include <set>

using namespace facesketch;
using namespace facesketch::stats;

namespace {

// Blobs of `perBlob` samples around `centres` (rows), with the given spread.
Eigen::MatrixXd blobs(Random& random, const Eigen::MatrixXd& centres, int perBlob, double spread)
{
    Eigen::MatrixXd X(centres.rows() * perBlob, centres.cols());
    for (Eigen::Index k = 0; k < centres.rows(); ++k)
        for (int i = 0; i < perBlob; ++i)
            X.row(k * perBlob + i) = centres.row(k) + spread * random.normalMatrix(1, centres.cols());
    return X;
}

double directObjective(const Eigen::MatrixXd& X, const Eigen::VectorXi& labels, const Eigen::MatrixXd& centres)
{
    double J = 0.0;
    for (Eigen::Index i = 0; i < X.rows(); ++i)
        J += (X.row(i) - centres.row(labels(i))).squaredNorm();
    return J;
}

} // namespace

TEST_CASE("kmeans: objective never increases and matches a direct computation")
{
    Random random(11);
    // Overlapping blobs in 6 dimensions so that Lloyd's iterations have work to do.
    const Eigen::MatrixXd X = blobs(random, 2.0 * random.normalMatrix(5, 6), 30, 1.0);
    const KMeansResult r = kmeans(X, 4);
    REQUIRE(r.converged);
    REQUIRE(r.objective.size() >= 2);
    for (size_t i = 1; i < r.objective.size(); ++i)
        CHECK(r.objective[i] <= r.objective[i - 1] * (1.0 + 1e-12));

    // The centres are the means of their members, and the recorded objective is eq. 4.1.
    Eigen::MatrixXd means = Eigen::MatrixXd::Zero(4, X.cols());
    Eigen::VectorXd counts = Eigen::VectorXd::Zero(4);
    for (Eigen::Index i = 0; i < X.rows(); ++i) {
        means.row(r.labels(i)) += X.row(i);
        counts(r.labels(i)) += 1.0;
    }
    REQUIRE(counts.minCoeff() >= 1.0);
    means.array().colwise() /= counts.array();
    CHECK((means - r.centres).cwiseAbs().maxCoeff() < 1e-12);
    const double J = directObjective(X, r.labels, r.centres);
    CHECK(std::abs(J - r.objective.back()) <= 1e-9 * J);

    // Converged: every sample is at least as close to its own centre as to any other.
    for (Eigen::Index i = 0; i < X.rows(); ++i)
        for (Eigen::Index k = 0; k < 4; ++k)
            CHECK((X.row(i) - r.centres.row(r.labels(i))).squaredNorm() <= (X.row(i) - r.centres.row(k)).squaredNorm() + 1e-9);
}

TEST_CASE("kmeans: seeding takes the sample nearest the mean, then the farthest ones")
{
    // 1D samples 0, 1, 2, 10, -5: the mean is 1.6, so sample 2 comes first; 10 is 8 away from
    // it (sample 3), then -5 is 7 away from its nearest centre (sample 4).
    Eigen::MatrixXd X(5, 1);
    X << 0.0, 1.0, 2.0, 10.0, -5.0;
    REQUIRE(kmedoidsSeeds(centredGram(X), 3) == std::vector<int> { 2, 3, 4 });
    // Duplicates are never picked twice.
    Eigen::MatrixXd same = Eigen::MatrixXd::Ones(4, 2);
    const std::vector<int> seeds = kmedoidsSeeds(centredGram(same), 4);
    REQUIRE(std::set<int>(seeds.begin(), seeds.end()).size() == 4);
}

TEST_CASE("kmeans: K-means++ seeds are distinct, reproducible and favour far samples")
{
    Random random(6);
    const Eigen::MatrixXd X = random.normalMatrix(30, 3);
    const Eigen::MatrixXd G = centredGram(X);
    const std::vector<int> a = kmeansPlusPlusSeeds(G, 10, 4);
    REQUIRE(a == kmeansPlusPlusSeeds(G, 10, 4));
    REQUIRE(std::set<int>(a.begin(), a.end()).size() == 10);
    // Two far clusters of ten and one sample: the second seed lands in the other cluster
    // (probability above 0.999 for every draw of the first, so it must for all 50 seeds).
    Eigen::MatrixXd two(20, 2);
    two.topRows(10) = 0.1 * random.normalMatrix(10, 2);
    two.bottomRows(10) = (0.1 * random.normalMatrix(10, 2)).array() + 100.0;
    for (std::uint64_t seed = 0; seed < 50; ++seed) {
        const std::vector<int> s = kmeansPlusPlusSeeds(centredGram(two), 2, seed);
        REQUIRE((s[0] < 10) != (s[1] < 10));
    }
    KMeansOptions options;
    options.seeding = Seeding::KMeansPlusPlus;
    const KMeansResult r = kmeans(two, 2, options);
    REQUIRE(r.objective.back() < 1.0);
}

TEST_CASE("kmeans: recovers well-separated clusters exactly")
{
    Random random(5);
    Eigen::MatrixXd centres(3, 4);
    centres << 0, 0, 0, 0, 20, 0, 0, 0, 0, 20, 0, 0;
    const Eigen::MatrixXd X = blobs(random, centres, 25, 1.0);
    const KMeansResult r = kmeans(X, 3);
    for (Eigen::Index k = 0; k < 3; ++k)
        for (int i = 1; i < 25; ++i)
            REQUIRE(r.labels(k * 25 + i) == r.labels(k * 25));
    REQUIRE(std::set<int> { r.labels(0), r.labels(25), r.labels(50) }.size() == 3);
    // With as many clusters as samples every sample is its own cluster and J = 0.
    const KMeansResult all = kmeans(X.topRows(6), 6);
    CHECK(all.objective.back() < 1e-9);
}

TEST_CASE("kmeans: the Gram-matrix and the sample paths agree")
{
    Random random(8);
    // d < n goes through the samples, kmeansGram through the Gram matrix.
    const Eigen::MatrixXd X = blobs(random, 3.0 * random.normalMatrix(4, 3), 20, 1.0);
    const KMeansResult direct = kmeans(X, 4);
    const KMeansResult gram = kmeansGram(centredGram(X), 4);
    REQUIRE(direct.seeds == gram.seeds);
    REQUIRE(direct.labels == gram.labels);
    REQUIRE(direct.objective.size() == gram.objective.size());
    CHECK(std::abs(direct.objective.back() - gram.objective.back()) <= 1e-9 * direct.objective.back());
    // A chosen first centre is kept.
    KMeansOptions options;
    options.firstSeed = 17;
    REQUIRE(kmeans(X, 4, options).seeds.front() == 17);
    options.firstSeed = 80;
    REQUIRE_THROWS_AS(kmeans(X, 4, options), Error);
}

TEST_CASE("kmeans: deterministic, and rejects NaN and a bad K")
{
    Random random(9);
    const Eigen::MatrixXd X = random.normalMatrix(40, 3);
    const KMeansResult a = kmeans(X, 5), b = kmeans(X, 5);
    REQUIRE(a.labels == b.labels);
    REQUIRE(a.objective == b.objective);

    Eigen::MatrixXd bad = X;
    bad(7, 2) = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(kmeans(bad, 3), Catch::Contains("X(7, 2)"));
    REQUIRE_THROWS_AS(kmeans(X, 0), Error);
    REQUIRE_THROWS_AS(kmeans(X, 41), Error);
}

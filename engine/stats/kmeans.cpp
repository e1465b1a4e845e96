#include "stats/kmeans.h"

#include "core/error.h"
#include "core/random.h"
#include "stats/check.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facesketch::stats {

namespace {

// The two places the samples can live. Both give squared distances between samples, to the
// mean of all samples (up to a constant) and to the means of the clusters of a labelling.

// Through the Gram matrix: O(n^2 K) per labelling, whatever d.
struct GramSpace {
    const Eigen::MatrixXd& G;

    Eigen::Index size() const { return G.rows(); }
    double distance(Eigen::Index i, Eigen::Index j) const { return std::max(0.0, G(i, i) + G(j, j) - 2.0 * G(i, j)); }
    Eigen::VectorXd toMean() const { return G.diagonal() - 2.0 * G.rowwise().mean(); }

    // |x_i - c_k|^2 = G_ii - 2/s_k sum_{j in k} G_ij + 1/s_k^2 sum_{j,l in k} G_jl.
    Eigen::MatrixXd toMeans(const Eigen::VectorXi& labels, int K) const
    {
        const Eigen::Index n = G.rows();
        Eigen::MatrixXd indicator = Eigen::MatrixXd::Zero(n, K);
        for (Eigen::Index i = 0; i < n; ++i)
            indicator(i, labels(i)) = 1.0;
        const Eigen::VectorXd size = indicator.colwise().sum().transpose();
        const Eigen::MatrixXd sums = G * indicator;
        Eigen::MatrixXd D(n, K);
        for (int k = 0; k < K; ++k) {
            if (size(k) == 0.0) {
                D.col(k).setConstant(std::numeric_limits<double>::infinity());
                continue;
            }
            const double self = indicator.col(k).dot(sums.col(k)) / (size(k) * size(k));
            D.col(k) = (G.diagonal() - 2.0 / size(k) * sums.col(k)).array() + self;
        }
        // Rounding can leave a sample that sits on its own mean slightly below zero.
        return D.cwiseMax(0.0);
    }
};

// Directly on the samples: O(n K d) per labelling, for many samples of low dimension
// (vertex positions in the segmentation), where an n by n matrix would not fit.
struct DataSpace {
    const Eigen::MatrixXd& X;

    Eigen::Index size() const { return X.rows(); }
    double distance(Eigen::Index i, Eigen::Index j) const { return (X.row(i) - X.row(j)).squaredNorm(); }
    Eigen::VectorXd toMean() const { return (X.rowwise() - X.colwise().mean()).rowwise().squaredNorm(); }

    Eigen::MatrixXd toMeans(const Eigen::VectorXi& labels, int K) const
    {
        const Eigen::MatrixXd C = means(X, labels, K);
        Eigen::MatrixXd D(X.rows(), K);
        for (int k = 0; k < K; ++k)
            D.col(k) = std::isfinite(C(k, 0)) ? (X.rowwise() - C.row(k)).rowwise().squaredNorm().eval()
                                              : Eigen::VectorXd::Constant(X.rows(), std::numeric_limits<double>::infinity());
        return D;
    }

    // K by d cluster means; a row of infinities for an empty cluster.
    static Eigen::MatrixXd means(const Eigen::MatrixXd& X, const Eigen::VectorXi& labels, int K)
    {
        Eigen::MatrixXd C = Eigen::MatrixXd::Zero(K, X.cols());
        Eigen::VectorXd size = Eigen::VectorXd::Zero(K);
        for (Eigen::Index i = 0; i < X.rows(); ++i) {
            C.row(labels(i)) += X.row(i);
            size(labels(i)) += 1.0;
        }
        for (int k = 0; k < K; ++k)
            C.row(k) = size(k) > 0.0 ? (C.row(k) / size(k)).eval()
                                     : Eigen::RowVectorXd::Constant(X.cols(), std::numeric_limits<double>::infinity());
        return C;
    }
};

void checkK(Eigen::Index n, int K, const char* who)
{
    if (K < 1 || K > n)
        fail(who, ": K = ", K, " outside [1, ", n, "]");
}

template <typename Space> std::vector<int> farthestFirst(const Space& space, int K, int first)
{
    const Eigen::Index n = space.size();
    if (first < 0) {
        Eigen::Index nearestMean = 0;
        space.toMean().minCoeff(&nearestMean);
        first = static_cast<int>(nearestMean);
    } else if (first >= n) {
        fail("kmeans: firstSeed = ", first, " outside [0, ", n, ")");
    }
    std::vector<int> seeds { first };
    Eigen::VectorXd nearest(n);
    for (Eigen::Index i = 0; i < n; ++i)
        nearest(i) = space.distance(i, first);
    nearest(first) = -1.0; // chosen samples are never picked again, even among duplicates
    while (static_cast<int>(seeds.size()) < K) {
        Eigen::Index next = 0;
        nearest.maxCoeff(&next);
        seeds.push_back(static_cast<int>(next));
        for (Eigen::Index i = 0; i < n; ++i)
            if (nearest(i) >= 0.0)
                nearest(i) = std::min(nearest(i), space.distance(i, next));
        nearest(next) = -1.0;
    }
    return seeds;
}

template <typename Space> std::vector<int> plusPlus(const Space& space, int K, std::uint64_t seed)
{
    const Eigen::Index n = space.size();
    Random random(seed);
    std::vector<int> seeds { static_cast<int>(random.index(n)) };
    Eigen::VectorXd nearest = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
    std::vector<bool> chosen(static_cast<size_t>(n), false);
    chosen[static_cast<size_t>(seeds[0])] = true;
    while (static_cast<int>(seeds.size()) < K) {
        const Eigen::Index last = seeds.back();
        for (Eigen::Index i = 0; i < n; ++i)
            nearest(i) = chosen[static_cast<size_t>(i)] ? 0.0 : std::min(nearest(i), space.distance(i, last));
        const double total = nearest.sum();
        Eigen::Index next = -1;
        if (total > 0.0) {
            double u = random.uniform() * total;
            for (Eigen::Index i = 0; i < n && next < 0; ++i) {
                if (nearest(i) > 0.0 && u < nearest(i))
                    next = i;
                u -= nearest(i);
            }
            // Rounding can carry u past the last positive entry; take that entry.
            for (Eigen::Index i = n - 1; next < 0 && i >= 0; --i)
                if (nearest(i) > 0.0)
                    next = i;
        } else {
            // Only duplicates of the chosen samples are left: take the first unchosen one.
            for (Eigen::Index i = 0; i < n && next < 0; ++i)
                if (!chosen[static_cast<size_t>(i)])
                    next = i;
        }
        seeds.push_back(static_cast<int>(next));
        chosen[static_cast<size_t>(next)] = true;
    }
    return seeds;
}

double objectiveOf(const Eigen::MatrixXd& D, const Eigen::VectorXi& labels)
{
    double J = 0.0;
    for (Eigen::Index i = 0; i < labels.size(); ++i)
        J += D(i, labels(i));
    return J;
}

// Gives every empty cluster the sample farthest from its own mean among clusters with two or
// more members. Removing that sample from its cluster lowers J by its distance at least, and
// as the sole member of the empty cluster it costs nothing.
template <typename Space> void refillEmptyClusters(const Space& space, Eigen::VectorXi& labels, int K)
{
    for (;;) {
        Eigen::VectorXi size = Eigen::VectorXi::Zero(K);
        for (Eigen::Index i = 0; i < labels.size(); ++i)
            ++size(labels(i));
        int empty = -1;
        for (int k = 0; k < K && empty < 0; ++k)
            if (size(k) == 0)
                empty = k;
        if (empty < 0)
            return;
        const Eigen::MatrixXd D = space.toMeans(labels, K);
        Eigen::Index far = -1;
        double farDistance = -1.0;
        for (Eigen::Index i = 0; i < labels.size(); ++i)
            if (size(labels(i)) > 1 && D(i, labels(i)) > farDistance) {
                far = i;
                farDistance = D(i, labels(i));
            }
        labels(far) = empty;
    }
}

template <typename Space> KMeansResult lloyd(const Space& space, int K, const KMeansOptions& options)
{
    KMeansResult result;
    result.seeds = options.seeding == Seeding::KMedoids ? farthestFirst(space, K, options.firstSeed) : plusPlus(space, K, options.seed);
    const Eigen::Index n = space.size();

    // Assign to the nearest seed (the medoids), then iterate on cluster means.
    Eigen::VectorXi labels(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        double best = std::numeric_limits<double>::infinity();
        for (int k = 0; k < K; ++k) {
            const double dist = space.distance(i, result.seeds[static_cast<size_t>(k)]);
            if (dist < best) {
                best = dist;
                labels(i) = k;
            }
        }
    }
    for (int k = 0; k < K; ++k)
        labels(result.seeds[static_cast<size_t>(k)]) = k;

    Eigen::MatrixXd D = space.toMeans(labels, K);
    result.objective.push_back(objectiveOf(D, labels));
    for (int it = 0; it < options.maxIterations; ++it) {
        Eigen::VectorXi next = labels;
        // Keep the current label on ties so the loop cannot cycle between equal solutions.
        for (Eigen::Index i = 0; i < n; ++i)
            for (int k = 0; k < K; ++k)
                if (D(i, k) < D(i, next(i)))
                    next(i) = k;
        refillEmptyClusters(space, next, K);
        result.iterations = it + 1;
        if (next == labels) {
            result.converged = true;
            break;
        }
        labels = next;
        D = space.toMeans(labels, K);
        result.objective.push_back(objectiveOf(D, labels));
    }
    result.labels = labels;
    return result;
}

} // namespace

Eigen::MatrixXd centredGram(const Eigen::MatrixXd& X)
{
    const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(X.rows(), X.rows());
    G.selfadjointView<Eigen::Lower>().rankUpdate(Xc);
    return G.selfadjointView<Eigen::Lower>();
}

std::vector<int> kmedoidsSeeds(const Eigen::MatrixXd& G, int K)
{
    if (G.cols() != G.rows())
        fail("kmedoidsSeeds: G is ", G.rows(), " by ", G.cols(), ", expected square");
    checkK(G.rows(), K, "kmedoidsSeeds");
    return farthestFirst(GramSpace { G }, K, -1);
}

std::vector<int> kmeansPlusPlusSeeds(const Eigen::MatrixXd& G, int K, std::uint64_t seed)
{
    if (G.cols() != G.rows())
        fail("kmeansPlusPlusSeeds: G is ", G.rows(), " by ", G.cols(), ", expected square");
    checkK(G.rows(), K, "kmeansPlusPlusSeeds");
    return plusPlus(GramSpace { G }, K, seed);
}

KMeansResult kmeansGram(const Eigen::MatrixXd& G, int K, const KMeansOptions& options)
{
    if (G.cols() != G.rows())
        fail("kmeans: G is ", G.rows(), " by ", G.cols(), ", expected square");
    requireFinite(G, "kmeans: G");
    checkK(G.rows(), K, "kmeans");
    return lloyd(GramSpace { G }, K, options);
}

KMeansResult kmeans(const Eigen::MatrixXd& X, int K, const KMeansOptions& options)
{
    requireFinite(X, "kmeans: X");
    checkK(X.rows(), K, "kmeans");
    KMeansResult result;
    if (X.cols() < X.rows()) {
        result = lloyd(DataSpace { X }, K, options);
    } else {
        const Eigen::MatrixXd G = centredGram(X);
        result = lloyd(GramSpace { G }, K, options);
    }
    result.centres = DataSpace::means(X, result.labels, K);
    return result;
}

} // namespace facesketch::stats

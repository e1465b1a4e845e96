#pragma once
// Hard clustering of samples: K-medoids seeding followed by K-means (Lloyd's iterations).
// Used to initialise the mixtures of PPCA (stats/mppca.h) and to segment the face
// (thesis 4.2.2).
//
// This work is based on:
//   Gunnarsson, "Sketching 3D Faces", PhD thesis 2010, section 4.2.1.1 (seeding then K-means);
//   Bishop, "Pattern Recognition and Machine Learning", 2006, section 9.1 (K-means, eq. 9.1);
//   Gonzalez, "Clustering to minimize the maximum intercluster distance", 1985
//   (farthest-first traversal);
//   Arthur and Vassilvitskii, "k-means++: the advantages of careful seeding", SODA 2007
//   (the alternative seeding used for the restarts of stats/mppca).
//
// Everything is deterministic: the K-medoids seeding has no randomness and the K-means++
// seeding draws from a seeded Random (core/random.h); ties go to the lowest index.
//
// Samples are rows. When d >= n the work is done on the n by n Gram matrix of the centred
// samples, so one iteration costs O(n^2 K) whatever d (the Gram matrix costs O(n^2 d) once):
// faces, n ~ 200 and d up to 75,000. When d < n it is done on the samples, O(n K d) per
// iteration: vertex positions, n up to 25,000 and d = 3.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace facesketch::stats {

enum class Seeding {
    /// Thesis 4.2.1.1: nearest the mean first, then farthest-first (kmedoidsSeeds).
    KMedoids,
    /// K-means++: each centre drawn with probability proportional to the squared distance
    /// to the nearest centre chosen so far (kmeansPlusPlusSeeds).
    KMeansPlusPlus,
};

struct KMeansOptions {
    /// Lloyd iterations after seeding; the loop stops earlier when no label changes.
    int maxIterations = 100;
    Seeding seeding = Seeding::KMedoids;
    /// KMedoids only: index of the first centre (the thesis' "specific criteria", e.g. the
    /// nose tip for the segmentation); -1 takes the sample nearest the mean of all samples.
    int firstSeed = -1;
    /// Seed of the K-means++ draws (unused by KMedoids).
    std::uint64_t seed = 1;
};

struct KMeansResult {
    /// n cluster labels in [0, K), one per sample.
    Eigen::VectorXi labels;
    /// K sample indices picked by the seeding, in the order picked.
    std::vector<int> seeds;
    /// K by d cluster means (empty when clustering from a Gram matrix).
    Eigen::MatrixXd centres;
    /// Objective J = sum_n ||x_n - mean of its cluster||^2 (thesis eq. 4.1) after the seeding
    /// assignment, then after every Lloyd iteration. Never increases.
    std::vector<double> objective;
    /// Lloyd iterations run; converged is true when the last one changed no label.
    int iterations = 0;
    bool converged = false;
};

/// K-medoids seeding on a Gram matrix: the first centre is the sample nearest the mean of all
/// samples; each further centre is the sample farthest from its nearest chosen centre.
/// @param[in] G  n by n Gram matrix of the (preferably centred) samples, G(i, j) = x_i . x_j
/// @param[in] K  number of centres, 1 <= K <= n
/// @return K distinct sample indices
///
/// The thesis maximises the *sum* of distances to the chosen centres; that rule can pick a
/// point right next to an existing centre when the other centres are far away, so we take
/// the maximum of the *smallest* distance instead (farthest-first traversal).
std::vector<int> kmedoidsSeeds(const Eigen::MatrixXd& G, int K);

/// K-means++ seeding on a Gram matrix (Arthur and Vassilvitskii 2007), drawn from
/// Random(seed). Returns K distinct sample indices; 1 <= K <= n.
std::vector<int> kmeansPlusPlusSeeds(const Eigen::MatrixXd& G, int K, std::uint64_t seed);

/// K-means from the seeds of options.seeding, working on a Gram matrix.
/// @param[in] G  n by n symmetric Gram matrix of the samples
/// @param[in] K  number of clusters, 1 <= K <= n
/// An empty cluster takes the sample farthest from its own cluster mean, which lowers J, so
/// every cluster keeps at least one sample. result.centres is left empty.
/// Throws Error if G is not square or holds a NaN, or K is out of range.
KMeansResult kmeansGram(const Eigen::MatrixXd& G, int K, const KMeansOptions& options = {});

/// K-means on samples: through centredGram(X) when d >= n, directly on X otherwise (the two
/// give the same labels up to rounding).
/// @param[in] X  n by d matrix, one sample per row
/// @param[in] K  number of clusters, 1 <= K <= n
/// @return labels, seeds, objective history and the K by d cluster means
/// Throws Error naming the row and column of a NaN or infinity in X, or if K or
/// options.firstSeed is out of range.
KMeansResult kmeans(const Eigen::MatrixXd& X, int K, const KMeansOptions& options = {});

/// n by n Gram matrix of the rows of X after subtracting their mean: Xc Xc^T. Centring keeps
/// the squared distances computed from it accurate (no cancellation against |x|^2).
Eigen::MatrixXd centredGram(const Eigen::MatrixXd& X);

} // namespace facesketch::stats

#include "pose/stroke_fps.h"

#include "core/error.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace facesketch::pose {

namespace {

double logSumExp(const Eigen::VectorXd& values)
{
    const double top = values.maxCoeff();
    return top + std::log((values.array() - top).exp().sum());
}

/// Per point of one stroke: which cluster it hits within `allowed` (or -1), and how well.
struct PointHit {
    int cluster = -1;
    double logDensity = -std::numeric_limits<double>::infinity();
    double responsibility = 0; ///< of the winner, within `allowed`
};

PointHit hitWithin(const FpClusters& clusters, const std::vector<int>& allowed, const Eigen::Vector3d& x, double maxMahalanobis)
{
    Eigen::VectorXd l(static_cast<Eigen::Index>(allowed.size()));
    for (std::size_t i = 0; i < allowed.size(); ++i)
        l(static_cast<Eigen::Index>(i)) = clusters.logDensity(allowed[i], x);
    Eigen::Index best = 0;
    l.maxCoeff(&best);
    PointHit hit;
    const int k = allowed[static_cast<std::size_t>(best)];
    if (clusters.mahalanobis(k, x) > maxMahalanobis)
        return hit;
    hit.cluster = k;
    hit.logDensity = l(best);
    hit.responsibility = std::exp(l(best) - logSumExp(l));
    return hit;
}

/// Step 6 for group g: its interior FPs picked again given the sketch-plane positions of its
/// ends read so far (the conditional Gaussian of the joint cluster covariance).
void followEnds(const FpClusters& clusters, const std::vector<PoseStrokePoints>& strokes, const std::vector<std::vector<int>>& pointCluster,
    std::size_t g, double endpointBonus, std::vector<IdentifiedFp>& best)
{
    std::vector<int> ends;
    for (int b : clusters.boundary[g])
        if (best[static_cast<std::size_t>(b)].fp >= 0)
            ends.push_back(b);
    if (ends.empty())
        return;
    const Eigen::MatrixXd& C = clusters.jointCovariance;
    const Eigen::Index m = 2 * static_cast<Eigen::Index>(ends.size());
    // The observed part: each end's two plane coordinates, A x with A = [0 .. P_b .. 0].
    Eigen::MatrixXd AC(m, C.cols());
    Eigen::VectorXd y(m);
    for (std::size_t i = 0; i < ends.size(); ++i) {
        const IdentifiedFp& end = best[static_cast<std::size_t>(ends[i])];
        const Eigen::Index row = 2 * static_cast<Eigen::Index>(i);
        AC.middleRows(row, 2) = end.plane * C.middleRows(3 * ends[i], 3);
        y.segment<2>(row) = end.plane * (end.position - clusters.mean[static_cast<std::size_t>(ends[i])]);
    }
    Eigen::MatrixXd S(m, m);
    for (std::size_t i = 0; i < ends.size(); ++i)
        S.middleCols(2 * static_cast<Eigen::Index>(i), 2)
            = AC.middleCols(3 * ends[i], 3) * best[static_cast<std::size_t>(ends[i])].plane.transpose();
    const Eigen::LLT<Eigen::MatrixXd> llt(S);
    if (llt.info() != Eigen::Success)
        return; // cannot happen with minStdMm > 0; the thesis' pick stands otherwise
    const Eigen::VectorXd weights = llt.solve(y);

    for (int k : clusters.groups[g]) {
        IdentifiedFp& fp = best[static_cast<std::size_t>(k)];
        const auto& bounds = clusters.boundary[g];
        if (fp.fp < 0 || fp.nudged || std::find(bounds.begin(), bounds.end(), k) != bounds.end())
            continue;
        const Eigen::MatrixXd cross = AC.middleCols(3 * k, 3); // m by 3: Cov(A x, x_k)
        const Eigen::Vector3d mean = clusters.mean[static_cast<std::size_t>(k)] + cross.transpose() * weights;
        const Eigen::Matrix3d covariance = C.block<3, 3>(3 * k, 3 * k) - cross.transpose() * llt.solve(cross);
        const Eigen::LLT<Eigen::Matrix3d> local(covariance);
        if (local.info() != Eigen::Success)
            continue;
        const double logNormaliser = -0.5 * std::log(std::pow(2 * std::numbers::pi, 3) * covariance.determinant());
        const PoseStrokePoints& stroke = strokes[static_cast<std::size_t>(fp.stroke)];
        const auto& hits = pointCluster[static_cast<std::size_t>(fp.stroke)];
        const int n = static_cast<int>(stroke.world.size());
        double bestScore = -std::numeric_limits<double>::infinity();
        int bestPoint = -1;
        for (int p = 0; p < n; ++p) {
            if (hits[static_cast<std::size_t>(p)] != k)
                continue;
            const Eigen::Vector3d d = stroke.world[static_cast<std::size_t>(p)] - mean;
            const double score = logNormaliser - 0.5 * d.dot(local.solve(d)) + (p == 0 || p == n - 1 ? endpointBonus : 0.0);
            if (score > bestScore) {
                bestScore = score;
                bestPoint = p;
            }
        }
        if (bestPoint < 0)
            continue;
        fp.point = bestPoint;
        fp.position = stroke.world[static_cast<std::size_t>(bestPoint)];
        fp.score = bestScore;
        fp.conditioned = true;
    }
}

} // namespace

const std::vector<FpGroup>& fpGroups()
{
    static const std::vector<FpGroup> groups = {
        { "brow_left", { "4.1", "4.3", "4.5" }, { "4.1", "4.5" } },
        { "brow_right", { "4.2", "4.4", "4.6" }, { "4.2", "4.6" } },
        { "upper_lid_left", { "3.1", "3.7", "3.11" }, { "3.7", "3.11" } },
        { "lower_lid_left", { "3.3", "3.7", "3.11" }, { "3.7", "3.11" } },
        { "upper_lid_right", { "3.2", "3.8", "3.12" }, { "3.8", "3.12" } },
        { "lower_lid_right", { "3.4", "3.8", "3.12" }, { "3.8", "3.12" } },
        { "upper_lip", { "8.1", "8.3", "8.4", "8.5", "8.6", "8.9", "8.10" }, { "8.3", "8.4" } },
        { "lower_lip", { "8.2", "8.3", "8.4", "8.7", "8.8" }, { "8.3", "8.4" } },
        { "nose", { "9.1", "9.2", "9.3", "9.15" }, { "9.1", "9.2" } },
        { "cheek_left", { "5.3" }, {} },
        { "cheek_right", { "5.4" }, {} },
        { "chin", { "2.1", "2.10" }, { "2.1" } },
    };
    return groups;
}

double FpClusters::logDensity(int k, const Eigen::Vector3d& x) const
{
    const Eigen::Vector3d d = x - mean[static_cast<std::size_t>(k)];
    return logNormaliser[static_cast<std::size_t>(k)] - 0.5 * d.dot(precision[static_cast<std::size_t>(k)] * d);
}

double FpClusters::mahalanobis(int k, const Eigen::Vector3d& x) const
{
    const Eigen::Vector3d d = x - mean[static_cast<std::size_t>(k)];
    return std::sqrt(std::max(0.0, d.dot(precision[static_cast<std::size_t>(k)] * d)));
}

FpClusters fpClusters(const FeaturePoints& fps, const Eigen::MatrixXd& fpTraining, const Vertices& neutral, const FpClusterOptions& options)
{
    const Eigen::Index F = fps.size();
    if (fpTraining.cols() != 3 * F)
        fail("FP training poses: ", fpTraining.cols(), " columns, expected 3 x ", F, " FPs");
    if (fpTraining.rows() < 2)
        fail("FP training poses: ", fpTraining.rows(), " rows, at least 2 are needed for a cluster's spread");
    if (!fpTraining.allFinite())
        fail("FP training poses: not finite");
    if (!std::isfinite(options.minStdMm) || options.minStdMm < 0)
        fail("FP clusters: minStdMm ", options.minStdMm, " is not >= 0");

    FpClusters clusters;
    const auto& groups = fpGroups();
    auto clusterOf = [&](const std::string& name) -> int {
        const auto it = std::find(clusters.names.begin(), clusters.names.end(), name);
        if (it != clusters.names.end())
            return static_cast<int>(it - clusters.names.begin());
        const int i = fps.index(name);
        if (i < 0)
            fail("FP clusters: the pose model has no feature point ", name, " (a sketchable FP, thesis 5.3)");
        const int v = fps.vertices[static_cast<std::size_t>(i)];
        if (v < 0 || v >= neutral.rows())
            fail("FP clusters: FP ", name, " is vertex ", v, ", the face has ", neutral.rows(), " vertices");
        const Eigen::Vector3d base = neutral.row(v).transpose();
        if (!base.allFinite())
            fail("FP clusters: the face's vertex ", v, " (FP ", name, ") is not finite");
        clusters.fp.push_back(i);
        clusters.names.push_back(name);
        clusters.mean.push_back(base); // plus the mean displacement, below
        return static_cast<int>(clusters.names.size()) - 1;
    };
    for (const FpGroup& group : groups) {
        std::vector<int> members, ends;
        for (const std::string& name : group.fps)
            members.push_back(clusterOf(name));
        for (const std::string& name : group.boundary)
            ends.push_back(clusterOf(name));
        clusters.groups.push_back(members);
        clusters.boundary.push_back(ends);
    }
    // The clusters' displacements side by side: their joint covariance, whose diagonal blocks
    // are each cluster's own.
    const Eigen::Index K = clusters.size();
    Eigen::MatrixXd d(fpTraining.rows(), 3 * K);
    for (Eigen::Index k = 0; k < K; ++k)
        d.middleCols(3 * k, 3) = fpTraining.middleCols(3 * clusters.fp[static_cast<std::size_t>(k)], 3);
    const Eigen::RowVectorXd meanDisplacement = d.colwise().mean();
    const Eigen::MatrixXd centred = d.rowwise() - meanDisplacement;
    clusters.jointCovariance = centred.transpose() * centred / static_cast<double>(d.rows());
    clusters.jointCovariance.diagonal().array() += options.minStdMm * options.minStdMm;
    for (Eigen::Index k = 0; k < K; ++k) {
        const auto c = static_cast<std::size_t>(k);
        clusters.mean[c] += meanDisplacement.segment<3>(3 * k).transpose();
        const Eigen::Matrix3d covariance = clusters.jointCovariance.block<3, 3>(3 * k, 3 * k);
        // A point that never moves in training and minStdMm 0 would leave a singular cluster.
        const Eigen::LLT<Eigen::Matrix3d> llt(covariance);
        if (llt.info() != Eigen::Success || covariance.determinant() <= 0)
            fail("FP clusters: FP ", clusters.names[c], " never moves in training; use minStdMm > 0");
        clusters.covariance.push_back(covariance);
        clusters.precision.push_back(llt.solve(Eigen::Matrix3d::Identity()));
        clusters.logNormaliser.push_back(-0.5 * std::log(std::pow(2 * std::numbers::pi, 3) * covariance.determinant()));
    }
    return clusters;
}

FpReading identifyFps(const FpClusters& clusters, const std::vector<PoseStrokePoints>& strokes, const FpReadingOptions& options)
{
    if (!std::isfinite(options.maxMahalanobis) || options.maxMahalanobis <= 0)
        fail("pose strokes: maxMahalanobis ", options.maxMahalanobis, " is not > 0");
    if (!std::isfinite(options.endpointWeight) || options.endpointWeight < 1)
        fail("pose strokes: endpointWeight ", options.endpointWeight, " is not >= 1");
    if (!std::isfinite(options.nudgeMm) || options.nudgeMm < 0)
        fail("pose strokes: nudgeMm ", options.nudgeMm, " is not >= 0");
    if (clusters.size() == 0)
        fail("pose strokes: no feature point clusters");

    std::vector<int> all(static_cast<std::size_t>(clusters.size()));
    for (int k = 0; k < clusters.size(); ++k)
        all[static_cast<std::size_t>(k)] = k;
    const auto& groups = fpGroups();
    const double endpointBonus = std::log(options.endpointWeight);

    FpReading reading;
    // Best candidate per cluster over all strokes (step 5).
    std::vector<IdentifiedFp> best(static_cast<std::size_t>(clusters.size()));
    // Per stroke and point: the cluster the point hit within the stroke's group (step 4), or -1.
    std::vector<std::vector<int>> pointCluster(strokes.size());
    auto offer = [&](int k, const PoseStrokePoints& stroke, int s, int p, const Eigen::Vector3d& at, double score, bool nudged) {
        IdentifiedFp& b = best[static_cast<std::size_t>(k)];
        if (b.fp >= 0 && b.score >= score)
            return;
        b.fp = clusters.fp[static_cast<std::size_t>(k)];
        b.name = clusters.names[static_cast<std::size_t>(k)];
        b.position = at;
        b.plane = stroke.plane;
        b.stroke = s;
        b.point = p;
        b.score = score;
        b.nudged = nudged;
    };

    // Every stroke is checked before any is read.
    for (std::size_t s = 0; s < strokes.size(); ++s) {
        const PoseStrokePoints& stroke = strokes[s];
        if (stroke.world.empty())
            fail("pose stroke ", s, ": no points");
        for (std::size_t p = 0; p < stroke.world.size(); ++p)
            if (!stroke.world[p].allFinite())
                fail("pose stroke ", s, ": point ", p, " is not finite");
        if (!stroke.plane.allFinite()
            || (stroke.plane * stroke.plane.transpose() - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff() > 1e-9)
            fail("pose stroke ", s, ": the rows of its sketch plane are not orthonormal");
    }

    for (std::size_t s = 0; s < strokes.size(); ++s) {
        const PoseStrokePoints& stroke = strokes[s];
        const int n = static_cast<int>(stroke.world.size());
        const int si = static_cast<int>(s);
        auto isEnd = [&](int p) { return p == 0 || p == n - 1; };

        // Step 3: the group the stroke hits most.
        std::vector<double> votes(groups.size(), 0.0), mass(groups.size(), 0.0);
        int hits = 0;
        int nearest = -1;
        double nearestDistance = std::numeric_limits<double>::infinity();
        for (int p = 0; p < n; ++p) {
            const Eigen::Vector3d& x = stroke.world[static_cast<std::size_t>(p)];
            const PointHit hit = hitWithin(clusters, all, x, options.maxMahalanobis);
            if (hit.cluster < 0) {
                for (int k = 0; k < clusters.size(); ++k)
                    if (clusters.mahalanobis(k, x) < nearestDistance) {
                        nearestDistance = clusters.mahalanobis(k, x);
                        nearest = k;
                    }
                continue;
            }
            ++hits;
            // An FP two groups share (a lip corner) says nothing about which of them the stroke
            // draws: its vote is split between them.
            std::vector<std::size_t> holders;
            for (std::size_t g = 0; g < groups.size(); ++g) {
                const std::vector<int>& members = clusters.groups[g];
                if (std::find(members.begin(), members.end(), hit.cluster) != members.end())
                    holders.push_back(g);
            }
            for (std::size_t g : holders)
                votes[g] += (isEnd(p) ? options.endpointWeight : 1.0) / static_cast<double>(holders.size());
        }
        // Ties (a stroke that hits only shared FPs) go to the group whose clusters explain all
        // of its points best: the sum over points of the best log density within the group.
        for (std::size_t g = 0; g < groups.size(); ++g) {
            if (votes[g] == 0)
                continue;
            for (int p = 0; p < n; ++p) {
                double best = -std::numeric_limits<double>::infinity();
                for (int k : clusters.groups[g])
                    best = std::max(best, clusters.logDensity(k, stroke.world[static_cast<std::size_t>(p)]));
                mass[g] += best;
            }
        }
        if (hits == 0)
            fail("pose stroke ", s, " hits no feature point cluster: its nearest is ", clusters.names[static_cast<std::size_t>(nearest)],
                " at Mahalanobis distance ", nearestDistance, ", the threshold is ", options.maxMahalanobis);
        std::size_t group = 0;
        for (std::size_t g = 1; g < groups.size(); ++g)
            if (votes[g] > votes[group] || (votes[g] == votes[group] && mass[g] > mass[group]))
                group = g;
        reading.strokeGroup.push_back(groups[group].name);
        reading.strokeHits.push_back(hits);

        // Steps 4 and 5 within the group.
        const std::vector<int>& members = clusters.groups[group];
        int firstEnd = -1; // the cluster the stroke's first point took, which the last may not take again
        for (int p = 0; p < n; ++p) {
            const Eigen::Vector3d& x = stroke.world[static_cast<std::size_t>(p)];
            const double bonus = isEnd(p) ? endpointBonus : 0.0;
            const PointHit hit = hitWithin(clusters, members, x, options.maxMahalanobis);
            pointCluster[s].push_back(hit.cluster);
            if (hit.cluster >= 0) {
                offer(hit.cluster, stroke, si, p, x, hit.logDensity + bonus, false);
                if (p == 0)
                    firstEnd = hit.cluster;
                continue;
            }
            if (!isEnd(p) || options.nudgeMm == 0)
                continue;
            int nudgedTo = -1;
            double nudgedScore = -std::numeric_limits<double>::infinity();
            for (int b : clusters.boundary[group]) {
                if (p > 0 && b == firstEnd)
                    continue;
                const Eigen::Vector3d towards = clusters.mean[static_cast<std::size_t>(b)] - x;
                const double distance = towards.norm();
                const Eigen::Vector3d moved = distance <= options.nudgeMm ? Eigen::Vector3d(clusters.mean[static_cast<std::size_t>(b)])
                                                                          : Eigen::Vector3d(x + towards * (options.nudgeMm / distance));
                const PointHit h = hitWithin(clusters, members, moved, options.maxMahalanobis);
                if (h.cluster == b && h.logDensity > nudgedScore) {
                    nudgedTo = b;
                    nudgedScore = h.logDensity;
                }
            }
            if (nudgedTo >= 0) {
                // The FP sits where the user ended the stroke: a short stroke asks for a narrower feature.
                offer(nudgedTo, stroke, si, p, x, nudgedScore + bonus, true);
                if (p == 0)
                    firstEnd = nudgedTo;
            }
        }
    }

    if (options.followEnds)
        for (std::size_t g = 0; g < groups.size(); ++g)
            followEnds(clusters, strokes, pointCluster, g, endpointBonus, best);

    for (const IdentifiedFp& fp : best)
        if (fp.fp >= 0)
            reading.fps.push_back(fp);
    return reading;
}

stats::Observations poseObservations(const FeaturePoints& fps, const Vertices& neutral, const FpReading& reading)
{
    stats::Observations observed;
    for (const IdentifiedFp& fp : reading.fps) {
        if (fp.fp < 0 || fp.fp >= fps.size())
            fail("pose observations: FP index ", fp.fp, " outside the model's ", fps.size(), " FPs");
        const int v = fps.vertices[static_cast<std::size_t>(fp.fp)];
        if (v < 0 || v >= neutral.rows())
            fail("pose observations: FP ", fp.name, " is vertex ", v, ", the face has ", neutral.rows(), " vertices");
        const Eigen::Vector3d displacement = fp.position - neutral.row(v).transpose();
        observed.addProjectedVertex(fp.fp, fp.plane, fp.plane * displacement);
    }
    return observed;
}

} // namespace facesketch::pose

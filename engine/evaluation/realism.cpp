#include "evaluation/realism.h"

#include "contours/curvature.h"
#include "core/error.h"
#include "core/parallel.h"
#include "dataset/manifest.h"
#include "dataset/mesh_quality.h"
#include "geometry/normals.h"
#include "geometry/similarity.h"
#include "registration/surface_query.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>

namespace facesketch::evaluation {

namespace {

const char* const kRegions[] = { "eyes", "brows", "nose", "mouth", "chin" };

void requireUsable(const FaceSet& set)
{
    if (set.shapes.rows() < 2)
        fail(set.name, ": ", set.shapes.rows(), " samples; the realism measures need at least 2");
    if (set.triangles.rows() == 0)
        fail(set.name, ": the skin has no triangle");
    if (set.shapes.cols() % 3 != 0)
        fail(set.name, ": shapes have ", set.shapes.cols(), " columns, not a multiple of 3");
    const Eigen::Index n = set.shapes.cols() / 3;
    if (set.triangles.size() > 0 && (set.triangles.minCoeff() < 0 || set.triangles.maxCoeff() >= n))
        fail(set.name, ": a triangle's vertex is outside [0, ", n, ")");
    for (Eigen::Index r = 0; r < set.shapes.rows(); ++r)
        for (Eigen::Index c = 0; c < set.shapes.cols(); ++c)
            if (!std::isfinite(set.shapes(r, c)))
                fail(set.name, ": sample ", r, " vertex ", c / 3, " has a non-finite coordinate (", set.shapes(r, c), ")");
    for (const auto& [name, v] : set.landmarks)
        if (v < 0 || v >= n)
            fail(set.name, ": landmark ", name, ": vertex ", v, " outside the skin [0, ", n, ")");
}

Vertices meanFace(const FaceSet& set)
{
    const Eigen::RowVectorXd mean = set.shapes.colwise().mean();
    return dataset::unflatten(mean);
}

// Every vertex's nearest central landmark within `radius` (its index into `points`), or -1.
std::vector<int> centralOwner(const Vertices& V, const Vertices& points, double radius)
{
    std::vector<int> owner(static_cast<size_t>(V.rows()), -1);
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
        double best = radius * radius;
        for (Eigen::Index k = 0; k < points.rows(); ++k) {
            const double d2 = (V.row(v) - points.row(k)).squaredNorm();
            if (d2 <= best) {
                best = d2;
                owner[static_cast<size_t>(v)] = static_cast<int>(k);
            }
        }
    }
    return owner;
}

struct Sample {
    double distance, weight;
    int group;     // index into kRegions
    bool enclosed; // enclosedVertices
    // Bending: the vertex's own mean curvature, and less the other surface's at the nearest point
    // (H interpolated over the nearest triangle), 1/m.
    double bend, bendDifference;
};

SurfaceDistance summarise(const std::string& region, std::vector<Sample> samples)
{
    SurfaceDistance s;
    s.region = region;
    std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.distance < b.distance; });
    double sum2 = 0;
    for (const Sample& x : samples) {
        s.area += x.weight;
        sum2 += x.weight * x.distance * x.distance;
        s.max = std::max(s.max, x.distance);
    }
    if (s.area <= 0)
        return s;
    s.rms = std::sqrt(sum2 / s.area);
    double below = 0;
    for (const Sample& x : samples) {
        below += x.weight;
        if (below >= 0.95 * s.area) {
            s.p95 = x.distance;
            break;
        }
    }
    return s;
}

// Distances from the central vertices of `from` to the skin of `to`, and their mean curvature
// (fromH) against `to`'s (toH, per vertex of to.mesh()) there, appended to `out`; returns the
// uncovered area and adds the enclosed area to `enclosedArea`.
double measure(const Vertices& from, const Triangles& fromF, const Eigen::VectorXd& fromH, const std::vector<int>& owner,
    const std::vector<int>& ownerGroup, const registration::SurfaceQuery& to, const Eigen::VectorXd& toH, double reach,
    std::vector<Sample>& out, double& enclosedArea)
{
    const Eigen::VectorXd area = vertexAreas(from, fromF);
    std::vector<int> central;
    for (Eigen::Index v = 0; v < from.rows(); ++v)
        if (owner[static_cast<size_t>(v)] >= 0 && area(v) > 0)
            central.push_back(static_cast<int>(v));
    const std::vector<char> enclosed = enclosedVertices(Mesh { from, fromF }, central, reach);
    double uncovered = 0;
    const Mesh& m = to.mesh();
    for (size_t k = 0; k < central.size(); ++k) {
        const int v = central[k];
        const registration::ClosestPoint c = to.closest(from.row(v).transpose());
        if (c.onBoundary)
            uncovered += area(v);
        if (enclosed[k])
            enclosedArea += area(v);
        const Eigen::Vector3d& b = c.barycentric;
        const double toBend = b(0) * toH(m.F(c.triangle, 0)) + b(1) * toH(m.F(c.triangle, 1)) + b(2) * toH(m.F(c.triangle, 2));
        out.push_back({ c.distance, area(v), ownerGroup[static_cast<size_t>(owner[static_cast<size_t>(v)])], enclosed[k] != 0, fromH(v),
            fromH(v) - toBend });
    }
    return uncovered;
}

// Mean curvature (k1 + k2) / 2 of every vertex of (V, F), in 1/m.
Eigen::VectorXd meanCurvature(const Vertices& V, const Triangles& F)
{
    const Curvature c = estimateCurvature(Mesh { V, F });
    return 500.0 * (c.k1 + c.k2); // 1/mm -> 1/m, halved
}

// Area-weighted sums of one squared quantity, over the whole central region (index 0, "all")
// and per region group g (index 1 + g, g indexing kRegions): add() counts a sample in both.
struct WeightedSums {
    std::vector<double> sum2 = std::vector<double>(1 + std::size(kRegions), 0.0);
    std::vector<double> weight = std::vector<double>(1 + std::size(kRegions), 0.0);
    void add(int group, double w, double value2)
    {
        for (const int k : { 0, 1 + group }) {
            sum2[static_cast<size_t>(k)] += w * value2;
            weight[static_cast<size_t>(k)] += w;
        }
    }
    double rms(size_t k) const { return weight[k] > 0 ? std::sqrt(sum2[k] / weight[k]) : 0.0; }
};

// The face-to-face spread of H over `set`'s central vertices (owner >= 0), times `scale`.
WeightedSums bendingSpread(const FaceSet& set, const std::vector<int>& owner, const std::vector<int>& ownerGroup, double scale)
{
    const Eigen::Index n = set.shapes.rows(), nv = set.shapes.cols() / 3;
    // The faces' curvatures, a batch at a time on all threads (most of `eval realism`'s time);
    // then the sums in face order, so the figures do not depend on the number of threads.
    constexpr Eigen::Index kBatch = 64;
    Eigen::MatrixXd H(nv, std::min(n, kBatch));
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(nv), m2 = Eigen::VectorXd::Zero(nv);
    for (Eigen::Index first = 0; first < n; first += kBatch) {
        const Eigen::Index count = std::min(kBatch, n - first);
        parallelFor(static_cast<int>(count), 0,
            [&](int k) { H.col(k) = scale * meanCurvature(dataset::unflatten(set.shapes.row(first + k)), set.triangles); });
        for (Eigen::Index k = 0; k < count; ++k) { // Welford, per vertex
            const Eigen::Index f = first + k;
            const Eigen::VectorXd delta = H.col(k) - mean;
            mean += delta / static_cast<double>(f + 1);
            m2 += delta.cwiseProduct(H.col(k) - mean);
        }
    }
    const Eigen::VectorXd area = vertexAreas(meanFace(set), set.triangles);
    WeightedSums spread;
    for (Eigen::Index v = 0; v < nv; ++v) {
        const int o = owner[static_cast<size_t>(v)];
        if (o >= 0 && area(v) > 0)
            spread.add(ownerGroup[static_cast<size_t>(o)], area(v), m2(v) / static_cast<double>(n - 1));
    }
    return spread;
}

Spectrum centralSpectrum(const FaceSet& set, const std::vector<int>& owner)
{
    std::vector<Eigen::Index> keep;
    for (size_t v = 0; v < owner.size(); ++v)
        if (owner[v] >= 0)
            keep.push_back(static_cast<Eigen::Index>(v));
    if (keep.empty())
        fail(set.name, ": no skin vertex lies in the central face region");
    const Eigen::VectorXd area = vertexAreas(meanFace(set), set.triangles);
    Eigen::MatrixXd sub(set.shapes.rows(), 3 * static_cast<Eigen::Index>(keep.size()));
    Eigen::VectorXd w(static_cast<Eigen::Index>(keep.size()));
    for (size_t k = 0; k < keep.size(); ++k) {
        sub.middleCols(3 * static_cast<Eigen::Index>(k), 3) = set.shapes.middleCols(3 * keep[k], 3);
        w(static_cast<Eigen::Index>(k)) = area(keep[k]);
    }
    return shapeSpectrum(sub, w);
}

} // namespace

std::string landmarkGroup(const std::string& landmark)
{
    std::string base = landmark;
    if (base.size() > 2 && (base.compare(base.size() - 2, 2, "_l") == 0 || base.compare(base.size() - 2, 2, "_r") == 0))
        base.resize(base.size() - 2);
    static const std::map<std::string, std::string> groups = { { "en", "eyes" }, { "ex", "eyes" }, { "ps", "eyes" }, { "pi", "eyes" },
        { "os", "brows" }, { "mf", "brows" }, { "g", "brows" }, { "n", "nose" }, { "s", "nose" }, { "cs1", "nose" }, { "prn", "nose" },
        { "sn", "nose" }, { "al", "nose" }, { "sbal", "nose" }, { "ls", "mouth" }, { "sto", "mouth" }, { "li", "mouth" }, { "ch", "mouth" },
        { "cph", "mouth" }, { "sl", "chin" }, { "pg", "chin" }, { "gn", "chin" } };
    const auto it = groups.find(base);
    return it == groups.end() ? std::string() : it->second;
}

FaceSet loadFaceSet(const dataset::Dataset& ds)
{
    const std::string where = ds.folder.string();
    const dataset::Manifest& m = ds.manifest;
    const dataset::Component* skin = m.component("skin");
    if (!skin)
        fail(where, ": components: no skin");
    FaceSet set;
    set.name = where;
    std::vector<Eigen::MatrixXd> parts;
    Eigen::Index rows = 0;
    for (dataset::Role role : { dataset::Role::Train, dataset::Role::Contour, dataset::Role::Test }) {
        parts.push_back(dataset::loadShapes(ds, role, "skin"));
        rows += parts.back().rows();
    }
    set.shapes.resize(rows, 3 * skin->size());
    Eigen::Index r = 0;
    for (const Eigen::MatrixXd& p : parts) {
        set.shapes.middleRows(r, p.rows()) = p;
        r += p.rows();
    }
    set.shapes *= dataset::millimetresPer(m.units, where + "/manifest.json");
    if (set.shapes.rows() < 2)
        fail(where, ": ", set.shapes.rows(), " samples; the realism measures need at least 2");

    std::vector<Eigen::Index> kept;
    for (Eigen::Index f = 0; f < m.topology.rows(); ++f)
        if (skin->contains(m.topology(f, 0)) && skin->contains(m.topology(f, 1)) && skin->contains(m.topology(f, 2)))
            kept.push_back(f);
    set.triangles.resize(static_cast<Eigen::Index>(kept.size()), 3);
    for (size_t k = 0; k < kept.size(); ++k)
        set.triangles.row(static_cast<Eigen::Index>(k)) = m.topology.row(kept[k]).array() - skin->begin;
    for (const auto& [name, v] : m.landmarks)
        if (skin->contains(v))
            set.landmarks[name] = v - skin->begin;
    // The manifest validated the axis ("+y", "-z", ...).
    set.up = Eigen::Vector3d::Zero();
    set.up(m.up[1] - 'x') = m.up[0] == '-' ? -1.0 : 1.0;
    return set;
}

std::vector<char> enclosedVertices(const Mesh& mesh, const std::vector<int>& vertices, double reach)
{
    const Vertices N = vertexNormals(mesh);
    const Eigen::Index nf = mesh.F.rows();
    Eigen::MatrixX3d lo(nf, 3), hi(nf, 3);
    for (Eigen::Index f = 0; f < nf; ++f) {
        lo.row(f) = mesh.V.row(mesh.F(f, 0)).cwiseMin(mesh.V.row(mesh.F(f, 1))).cwiseMin(mesh.V.row(mesh.F(f, 2)));
        hi.row(f) = mesh.V.row(mesh.F(f, 0)).cwiseMax(mesh.V.row(mesh.F(f, 1))).cwiseMax(mesh.V.row(mesh.F(f, 2)));
    }
    std::vector<char> out(vertices.size(), 0);
    for (size_t k = 0; k < vertices.size(); ++k) {
        const int v = vertices[k];
        const Eigen::Vector3d n = N.row(v).transpose();
        if (n.squaredNorm() == 0)
            continue;
        const Eigen::Vector3d p = mesh.V.row(v).transpose() + 0.01 * n, q = mesh.V.row(v).transpose() + reach * n;
        const Eigen::RowVector3d slo = p.cwiseMin(q).transpose(), shi = p.cwiseMax(q).transpose();
        for (Eigen::Index f = 0; f < nf && !out[k]; ++f) {
            if ((lo.row(f).array() > shi.array()).any() || (hi.row(f).array() < slo.array()).any())
                continue;
            if (mesh.F(f, 0) == v || mesh.F(f, 1) == v || mesh.F(f, 2) == v)
                continue;
            out[k] = dataset::segmentHitsTriangle(
                p, q, mesh.V.row(mesh.F(f, 0)).transpose(), mesh.V.row(mesh.F(f, 1)).transpose(), mesh.V.row(mesh.F(f, 2)).transpose());
        }
    }
    return out;
}

Eigen::VectorXd vertexAreas(const Vertices& V, const Triangles& F)
{
    Eigen::VectorXd area = Eigen::VectorXd::Zero(V.rows());
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
        const double third = (b - a).cross(c - a).norm() / 6.0;
        for (int k = 0; k < 3; ++k)
            area(F(f, k)) += third;
    }
    return area;
}

Asymmetry antisymmetricShare(const FaceSet& set, const Eigen::VectorXd& weights)
{
    const Eigen::Index nv = set.shapes.cols() / 3;
    if (weights.size() != nv)
        fail(set.name, ": antisymmetric share: ", weights.size(), " weights for ", nv, " vertices");
    if (!(weights.array() >= 0).all())
        fail(set.name, ": antisymmetric share: a weight is negative or NaN (", weights.minCoeff(), ")");
    const Vertices mean = meanFace(set);

    // The mirror plane n . x = c: n the mean direction from each "NAME_r" to its "NAME_l", c the
    // median of their midpoints along n (as sketch/symmetry.h); without pairs, x = mean x.
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> pairs;
    for (const auto& [name, right] : set.landmarks)
        if (name.size() > 2 && name.compare(name.size() - 2, 2, "_r") == 0) {
            const auto left = set.landmarks.find(name.substr(0, name.size() - 2) + "_l");
            if (left != set.landmarks.end()) {
                pairs.push_back({ mean.row(right).transpose(), mean.row(left->second).transpose() });
                n += (pairs.back().second - pairs.back().first).normalized();
            }
        }
    double c = 0;
    if (pairs.empty() || n.norm() < 1e-9) {
        n = Eigen::Vector3d::UnitX();
        c = mean.col(0).mean();
    } else {
        n.normalize();
        std::vector<double> middles;
        for (const auto& [r, l] : pairs)
            middles.push_back(n.dot(0.5 * (r + l)));
        std::nth_element(middles.begin(), middles.begin() + static_cast<std::ptrdiff_t>(middles.size() / 2), middles.end());
        c = middles[middles.size() / 2];
    }
    const Eigen::Matrix3d R = Eigen::Matrix3d::Identity() - 2 * n * n.transpose();

    // Each weighted vertex's partner: the vertex nearest its mirror image, if within the
    // vertex's mean edge length (an exactly symmetric topology pairs each vertex with its
    // mirror vertex; ICT-FaceKit's, which is not, with its nearest neighbour there).
    Eigen::VectorXd edgeSum = Eigen::VectorXd::Zero(nv), edgeCount = Eigen::VectorXd::Zero(nv);
    for (Eigen::Index f = 0; f < set.triangles.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = set.triangles(f, k), b = set.triangles(f, (k + 1) % 3);
            const double e = (mean.row(a) - mean.row(b)).norm();
            edgeSum(a) += e, edgeCount(a) += 1, edgeSum(b) += e, edgeCount(b) += 1;
        }
    Asymmetry a;
    int weighted = 0;
    double antisymmetric = 0, total = 0;
    for (Eigen::Index v = 0; v < nv; ++v) {
        if (weights(v) <= 0)
            continue;
        ++weighted;
        const Eigen::Vector3d image = R * mean.row(v).transpose() + 2 * c * n;
        Eigen::Index partner = 0;
        const double miss = std::sqrt((mean.rowwise() - image.transpose()).rowwise().squaredNorm().minCoeff(&partner));
        if (edgeCount(v) == 0 || miss > edgeSum(v) / edgeCount(v))
            continue;
        ++a.pairedVertices;
        for (Eigen::Index f = 0; f < set.shapes.rows(); ++f) {
            const Eigen::Vector3d d = set.shapes.row(f).segment<3>(3 * v).transpose() - mean.row(v).transpose();
            const Eigen::Vector3d dp = set.shapes.row(f).segment<3>(3 * partner).transpose() - mean.row(partner).transpose();
            antisymmetric += weights(v) * (0.5 * (d - R * dp)).squaredNorm();
            total += weights(v) * d.squaredNorm();
        }
    }
    if (weighted == 0)
        fail(set.name, ": antisymmetric share: no vertex has a positive weight");
    if (2 * a.pairedVertices < weighted) {
        a.message = cat(set.name, ": only ", a.pairedVertices, " of ", weighted,
            " weighted vertices have a vertex within their mean edge length of their mirror image");
        a.pairedVertices = 0;
        return a;
    }
    a.measured = true;
    a.share = total > 0 ? antisymmetric / total : 0.0;
    return a;
}

Eigen::Vector3d placementSpread(const FaceSet& set, const std::vector<std::string>& landmarks)
{
    if (landmarks.empty())
        fail(set.name, ": placement needs at least one landmark");
    const Eigen::Index n = set.shapes.rows();
    if (n < 2)
        fail(set.name, ": placement needs at least 2 samples, it has ", n);
    Eigen::MatrixXd centroids = Eigen::MatrixXd::Zero(n, 3);
    for (const std::string& l : landmarks) {
        const auto it = set.landmarks.find(l);
        if (it == set.landmarks.end())
            fail(set.name, ": placement: no landmark ", l);
        centroids += set.shapes.middleCols(3 * it->second, 3);
    }
    centroids /= static_cast<double>(landmarks.size());
    const Eigen::MatrixXd centred = centroids.rowwise() - centroids.colwise().mean();
    return (centred.colwise().squaredNorm() / static_cast<double>(n - 1)).cwiseSqrt().transpose();
}

Proportions faceProportions(const FaceSet& set)
{
    Proportions p;
    const Eigen::RowVectorXd mean = set.shapes.colwise().mean();
    std::map<std::string, Eigen::Vector3d> at;
    for (const char* name : { "en_l", "en_r", "ex_l", "ex_r", "sn", "ch_l", "ch_r" }) {
        const auto it = set.landmarks.find(name);
        if (it == set.landmarks.end()) {
            p.message = set.name + ": no landmark " + name;
            return p;
        }
        at[name] = mean.segment<3>(3 * it->second).transpose();
    }
    const Eigen::Vector3d eyes = (at["en_l"] + at["en_r"] + at["ex_l"] + at["ex_r"]) / 4;
    p.biocular = (at["ex_l"] - at["ex_r"]).norm();
    p.eyesToSn = (eyes - at["sn"]).dot(set.up);
    p.eyesToMouth = (eyes - (at["ch_l"] + at["ch_r"]) / 2).dot(set.up);
    p.measured = true;
    return p;
}

Spectrum shapeSpectrum(const Eigen::MatrixXd& shapes, const Eigen::VectorXd& weights)
{
    if (shapes.rows() < 2)
        fail("shape spectrum: ", shapes.rows(), " samples; at least 2 are needed");
    if (weights.size() != 0 && 3 * weights.size() != shapes.cols())
        fail("shape spectrum: ", weights.size(), " weights for ", shapes.cols() / 3, " vertices");
    if (weights.size() != 0 && !(weights.minCoeff() >= 0))
        fail("shape spectrum: a weight is negative or NaN (", weights.minCoeff(), ")");
    Eigen::MatrixXd X = shapes.rowwise() - shapes.colwise().mean();
    if (weights.size() != 0)
        for (Eigen::Index v = 0; v < weights.size(); ++v)
            X.middleCols(3 * v, 3) *= std::sqrt(weights(v));
    // The eigenvalues of the samples-by-samples Gram matrix X X^T are the squared singular
    // values of X (at most #samples non-zero), so never a 3#V square covariance. Not the SVD of
    // X itself: Eigen's BDCSVD on 250 faces by 15,690 coordinates raises a floating-point
    // exception in its secular-equation search (harmless in a release build, a trap in the
    // tests' debug builds), and the Gram route is cheaper (eval realism 3.7 -> 1.8 s on 250 high
    // faces against an ICT import; every variance the same to 1e-13). Round-off can leave the
    // smallest eigenvalues a little below 0: they are 0.
    const Eigen::MatrixXd gram = X * X.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram, Eigen::EigenvaluesOnly);
    if (eigen.info() != Eigen::Success)
        fail("shape spectrum: the eigen-decomposition of the ", gram.rows(), " x ", gram.cols(), " Gram matrix did not converge");
    Spectrum s;
    s.samples = static_cast<int>(shapes.rows());
    s.dimensions = static_cast<int>(shapes.cols());
    const double n1 = static_cast<double>(shapes.rows() - 1);
    const Eigen::VectorXd& lambda = eigen.eigenvalues(); // ascending
    for (Eigen::Index k = lambda.size() - 1; k >= 0; --k)
        s.variances.push_back(std::max(0.0, lambda(k)) / n1);
    for (double v : s.variances)
        s.totalVariance += v;
    const auto count = [&](double fraction) {
        double sum = 0;
        for (size_t k = 0; k < s.variances.size(); ++k) {
            sum += s.variances[k];
            if (sum >= fraction * s.totalVariance)
                return static_cast<int>(k + 1);
        }
        return static_cast<int>(s.variances.size());
    };
    s.modes90 = count(0.90);
    s.modes95 = count(0.95);
    s.modes99 = count(0.99);
    return s;
}

RealismReport evaluateRealism(const FaceSet& data, const FaceSet& reference, const RealismOptions& options)
{
    requireUsable(data);
    requireUsable(reference);
    if (std::isnan(options.regionRadius) || options.regionRadius <= 0)
        fail("eval realism: region radius ", options.regionRadius, " mm is not positive");
    if (!std::isfinite(options.enclosedReach) || options.enclosedReach <= 0)
        fail("eval realism: enclosed reach ", options.enclosedReach, " mm is not a positive number");

    RealismReport report;
    std::vector<int> groupOf; // per shared landmark, index into kRegions
    for (const auto& [name, v] : data.landmarks) {
        const std::string g = landmarkGroup(name);
        if (g.empty() || !reference.landmarks.count(name))
            continue;
        report.landmarks.push_back(name);
        groupOf.push_back(static_cast<int>(std::find(std::begin(kRegions), std::end(kRegions), g) - std::begin(kRegions)));
    }
    if (report.landmarks.size() < 4) {
        std::string shared;
        for (const std::string& l : report.landmarks)
            shared += (shared.empty() ? "" : ", ") + l;
        fail(data.name, " and ", reference.name, ": ", report.landmarks.size(), " shared central landmarks (",
            shared.empty() ? "none" : shared, "); the alignment needs at least 4");
    }

    const Vertices dataMean = meanFace(data), refMean = meanFace(reference);
    const auto n = static_cast<Eigen::Index>(report.landmarks.size());
    Vertices from(n, 3), to(n, 3);
    for (Eigen::Index k = 0; k < n; ++k) {
        const std::string& l = report.landmarks[static_cast<size_t>(k)];
        from.row(k) = dataMean.row(data.landmarks.at(l));
        to.row(k) = refMean.row(reference.landmarks.at(l));
    }
    const Similarity sim = fitSimilarity(from, to);
    report.alignmentScale = sim.scale;
    report.landmarkRms = std::sqrt((sim.apply(from) - to).rowwise().squaredNorm().mean());

    const Vertices dataAligned = sim.apply(dataMean);
    const std::vector<int> dataOwner = centralOwner(dataAligned, to, options.regionRadius);
    const std::vector<int> refOwner = centralOwner(refMean, to, options.regionRadius);

    const registration::SurfaceQuery dataSurface(Mesh { dataAligned, data.triangles });
    const registration::SurfaceQuery refSurface(Mesh { refMean, reference.triangles });
    std::vector<Sample> all;
    const double reach = options.enclosedReach;
    const Eigen::VectorXd dataH = meanCurvature(dataAligned, data.triangles), refH = meanCurvature(refMean, reference.triangles);
    report.dataUncovered
        = measure(dataAligned, data.triangles, dataH, dataOwner, groupOf, refSurface, refH, reach, all, report.dataEnclosed);
    for (const Sample& s : all)
        report.dataArea += s.weight;
    const size_t dataCount = all.size();
    report.referenceUncovered
        = measure(refMean, reference.triangles, refH, refOwner, groupOf, dataSurface, dataH, reach, all, report.referenceEnclosed);
    for (size_t k = dataCount; k < all.size(); ++k)
        report.referenceArea += all[k].weight;

    report.distances.push_back(summarise("all", all));
    std::vector<Sample> open;
    std::copy_if(all.begin(), all.end(), std::back_inserter(open), [](const Sample& s) { return !s.enclosed; });
    report.open = summarise("open", std::move(open));
    for (int g = 0; g < static_cast<int>(std::size(kRegions)); ++g) {
        std::vector<Sample> part;
        for (const Sample& s : all)
            if (s.group == g)
                part.push_back(s);
        if (!part.empty())
            report.distances.push_back(summarise(kRegions[g], std::move(part)));
    }

    WeightedSums difference, dataOwn, refOwn;
    for (size_t k = 0; k < all.size(); ++k) {
        const Sample& x = all[k];
        difference.add(x.group, x.weight, x.bendDifference * x.bendDifference);
        (k < dataCount ? dataOwn : refOwn).add(x.group, x.weight, x.bend * x.bend);
    }
    const WeightedSums dataSpread = bendingSpread(data, dataOwner, groupOf, 1.0 / sim.scale);
    const WeightedSums refSpread = bendingSpread(reference, refOwner, groupOf, 1.0);
    for (size_t k = 0; k < difference.weight.size(); ++k) {
        if (difference.weight[k] <= 0)
            continue;
        report.bending.push_back({ k == 0 ? std::string("all") : std::string(kRegions[k - 1]), dataOwn.rms(k), refOwn.rms(k),
            difference.rms(k), dataSpread.rms(k), refSpread.rms(k) });
    }

    report.dataSkin = shapeSpectrum(data.shapes);
    report.referenceSkin = shapeSpectrum(reference.shapes);
    report.dataCentral = centralSpectrum(data, dataOwner);
    report.referenceCentral = centralSpectrum(reference, refOwner);
    const auto centralAreas = [](const FaceSet& set, const std::vector<int>& owner) {
        Eigen::VectorXd w = vertexAreas(meanFace(set), set.triangles);
        for (size_t v = 0; v < owner.size(); ++v)
            if (owner[v] < 0)
                w(static_cast<Eigen::Index>(v)) = 0;
        return w;
    };
    report.dataAsymmetry = antisymmetricShare(data, centralAreas(data, dataOwner));
    report.referenceAsymmetry = antisymmetricShare(reference, centralAreas(reference, refOwner));
    report.dataPlacement = placementSpread(data, report.landmarks);
    report.referencePlacement = placementSpread(reference, report.landmarks);
    report.dataProportions = faceProportions(data);
    report.referenceProportions = faceProportions(reference);
    return report;
}

} // namespace facesketch::evaluation

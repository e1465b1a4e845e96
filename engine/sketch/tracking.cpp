#include "sketch/tracking.h"

#include "core/error.h"
#include "sketch/symmetry.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <set>

namespace facesketch::sketch {

namespace {

// Singular values below this (relative to the largest) count as a missing direction when
// constraints of several views are stacked: two views 10 degrees apart still span 3D.
constexpr double kRankTolerance = 0.1;

Eigen::Vector3d viewAxisOf(const Eigen::Matrix<double, 2, 3>& P)
{
    return P.row(0).transpose().cross(P.row(1).transpose()).normalized();
}

// Rows of noise 0 among noisy ones: pinned, in effect, without dividing by zero.
constexpr double kExactVariance = 1e-8; // mm^2

// The constraints' rows weighted by their inverse variances: the information matrix
// J = sum a a^T / n and h = sum a b / n give the position's mean J^+ h, measured along J's
// eigenvectors with variances 1 / lambda. Directions no row touches (lambda ~ 0) stay
// unmeasured; two views a few degrees apart measure the direction between them, weakly.
void addWeighted(stats::Observations& observations, Eigen::Index vertex, const std::vector<VertexConstraint>& constraints)
{
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    Eigen::Vector3d h = Eigen::Vector3d::Zero();
    for (const VertexConstraint& c : constraints)
        for (int i = 0; i < c.rows; ++i) {
            const Eigen::Vector3d a = c.A.row(i).transpose();
            const double w = 1.0 / std::max(c.noise[i], kExactVariance);
            J += w * a * a.transpose();
            h += w * c.b[i] * a;
        }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(J);
    const Eigen::Vector3d& lambda = eigen.eigenvalues(); // ascending
    Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
    Eigen::Vector3d values = Eigen::Vector3d::Zero(), variances = Eigen::Vector3d::Zero();
    int rows = 0;
    for (int j = 2; j >= 0; --j) {
        if (!(lambda[j] > 1e-9 * lambda[2]))
            break;
        const Eigen::Vector3d v = eigen.eigenvectors().col(j);
        R.row(rows) = v.transpose();
        values[rows] = v.dot(h) / lambda[j];
        variances[rows] = 1.0 / lambda[j];
        ++rows;
    }
    observations.addVertexRows(vertex, R, rows, values, variances);
}

} // namespace

void addCombined(stats::Observations& observations, Eigen::Index vertex, const std::vector<VertexConstraint>& constraints)
{
    if (constraints.empty())
        return;
    const bool noisy = std::any_of(
        constraints.begin(), constraints.end(), [](const VertexConstraint& c) { return (c.noise.head(c.rows).array() > 0.0).any(); });
    if (noisy) {
        addWeighted(observations, vertex, constraints);
        return;
    }
    if (constraints.size() == 1 && constraints[0].rows == 3) {
        // A 3D constraint's rows are orthonormal: its position is A^T b.
        observations.addVertex(vertex, constraints[0].A.transpose() * constraints[0].b);
        return;
    }
    if (constraints.size() == 1 && constraints[0].rows == 2) {
        observations.addProjectedVertex(vertex, constraints[0].A.topRows<2>(), constraints[0].b.head<2>());
        return;
    }
    if (constraints.size() == 1 && constraints[0].rows == 1) {
        observations.addVertexAlong(vertex, constraints[0].A.row(0).transpose(), constraints[0].b[0]);
        return;
    }
    int rows = 0;
    for (const VertexConstraint& c : constraints)
        rows += c.rows;
    Eigen::MatrixXd A(rows, 3);
    Eigen::VectorXd b(rows);
    int r = 0;
    for (const VertexConstraint& c : constraints) {
        A.middleRows(r, c.rows) = c.A.topRows(c.rows);
        b.segment(r, c.rows) = c.b.head(c.rows);
        r += c.rows;
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& s = svd.singularValues();
    int rank = 0;
    for (Eigen::Index i = 0; i < s.size(); ++i)
        rank += s[i] > kRankTolerance * s[0] ? 1 : 0;
    // Least squares within the spanned directions only (minimum norm across the others).
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < rank; ++i)
        x += svd.matrixV().col(i) * (svd.matrixU().col(i).dot(b) / s[i]);
    if (rank == 3) {
        observations.addVertex(vertex, x);
    } else if (rank == 2) {
        const Eigen::Matrix<double, 2, 3> P = svd.matrixV().leftCols<2>().transpose();
        observations.addProjectedVertex(vertex, P, P * x);
    } else {
        // All rows along one direction (across-stroke constraints of strokes drawn along one
        // another): that direction.
        const Eigen::Vector3d d = svd.matrixV().col(0);
        observations.addVertexAlong(vertex, d, d.dot(x));
    }
}

TrackingModel::TrackingModel(const stats::FaceModel& model, const TrackingOptions& options)
    : model_(model)
    , options_(options)
{
    if (model.meanFace.size() == 0 || model.meanFace.size() % 3 != 0)
        fail("TrackingModel: the model has no mean face");
    // isfinite first: an ordered comparison with NaN raises FE_INVALID (a trap in debug tests).
    if (!std::isfinite(options.supersedeRadius) || options.supersedeRadius < 0)
        fail("TrackingModel: supersedeRadius must be a finite distance >= 0 mm, found ", options.supersedeRadius);
    if (!std::isfinite(options.supersedeAngleDeg) || options.supersedeAngleDeg < 0 || options.supersedeAngleDeg > 180)
        fail("TrackingModel: supersedeAngleDeg must lie in [0, 180], found ", options.supersedeAngleDeg);
    if (options.robustPasses < 0 || !std::isfinite(options.robustK) || options.robustK <= 0)
        fail("TrackingModel: robustPasses must be >= 0 and robustK a finite number > 0, found ", options.robustPasses, " and ",
            options.robustK);
    for (const auto& [name, sigma] : { std::pair { "planeNoiseMm", options.planeNoiseMm }, { "depthNoiseMm", options.depthNoiseMm } })
        if (!std::isfinite(sigma) || sigma < 0)
            fail("TrackingModel: ", name, " must be a finite distance >= 0 mm, found ", sigma);
    TrackingState start;
    start.constraints.resize(static_cast<size_t>(model.vertexCount()));
    start.face = model.meanFace;
    history_.push_back(std::move(start));
}

int TrackingModel::observedVertices() const
{
    int n = 0;
    for (const auto& c : state().constraints)
        n += c.empty() ? 0 : 1;
    return n;
}

std::vector<char> TrackingModel::drawnVertices(const Eigen::Vector3d& viewAxis, int exceptStroke) const
{
    const double cosLimit = std::cos(options_.supersedeAngleDeg * M_PI / 180.0);
    const auto& constraints = state().constraints;
    std::vector<char> drawn(constraints.size(), 0);
    for (size_t v = 0; v < constraints.size(); ++v)
        for (const VertexConstraint& c : constraints[v])
            if (c.stroke != exceptStroke && (c.rows == 3 || c.viewAxis.dot(viewAxis) >= cosLimit))
                drawn[v] = 1;
    return drawn;
}

stats::Observations TrackingModel::observations() const
{
    stats::Observations obs;
    const auto& constraints = state().constraints;
    for (size_t v = 0; v < constraints.size(); ++v)
        addCombined(obs, static_cast<Eigen::Index>(v), constraints[v]);
    return obs;
}

Mesh TrackingModel::faceMesh() const
{
    Mesh mesh;
    mesh.F = model_.triangles;
    mesh.V = asVertices(face());
    return mesh;
}

void TrackingModel::apply(const StrokeReading& reading, const ApplyOptions& options)
{
    const Eigen::Index nv = model_.vertexCount();
    // Everything is checked before the state is touched.
    if (reading.observations.empty())
        fail("tracking: the stroke's reading pins no vertex");
    const bool anyPlane = [&] {
        for (const VertexObservation& o : reading.observations)
            if (o.viewPlaneOnly || !o.acrossStroke.isZero())
                return true;
        return false;
    }();
    const Eigen::Matrix<double, 2, 3>& P = reading.viewPlane;
    const bool planeValid = P.allFinite() && ((P * P.transpose()) - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff() <= 1e-9;
    if (anyPlane && !planeValid)
        fail("tracking: the reading's viewPlane rows are not orthonormal (needed by its view-plane observations)");
    std::set<std::uint32_t> seen;
    for (size_t i = 0; i < reading.observations.size(); ++i) {
        const VertexObservation& o = reading.observations[i];
        if (o.vertex >= static_cast<std::uint64_t>(nv))
            fail("tracking: observations[", i, "].vertex ", o.vertex, " outside [0, ", nv, ")");
        if (!o.position.allFinite())
            fail("tracking: observations[", i, "].position of vertex ", o.vertex, " is not finite");
        if (!o.acrossStroke.isZero()
            && (!o.acrossStroke.allFinite() || std::abs(o.acrossStroke.norm() - 1) > 1e-6
                || (planeValid && std::abs(viewAxisOf(P).dot(o.acrossStroke)) > 1e-6)))
            fail("tracking: observations[", i, "].acrossStroke of vertex ", o.vertex, " is not a unit vector in the view plane");
        if (!seen.insert(o.vertex).second)
            fail("tracking: observations[", i, "]: vertex ", o.vertex, " is observed twice by one stroke");
    }
    if (options.mirror && options.mirror->size() != nv)
        fail("tracking: the mirror map has ", options.mirror->size(), " vertices, the model ", nv);

    TrackingState next = state();
    next.strokes += 1;
    const int stroke = next.strokes;
    // Without a view plane (every observation in 3D) the stroke has no view to compare: it
    // supersedes whatever lies near it.
    const bool hasView = planeValid;
    const Eigen::Vector3d axis = hasView ? viewAxisOf(P) : Eigen::Vector3d::UnitZ();
    const double cosLimit = std::cos(options_.supersedeAngleDeg * M_PI / 180.0);
    const double planeVariance = options_.planeNoiseMm * options_.planeNoiseMm;
    const double depthVariance = options_.depthNoiseMm * options_.depthNoiseMm;

    // New constraints per vertex: the stroke's own, then its mirror images where the stroke
    // did not itself map.
    std::vector<std::pair<std::uint32_t, VertexConstraint>> added;
    for (const VertexObservation& o : reading.observations) {
        VertexConstraint c;
        c.stroke = stroke;
        c.viewAxis = axis;
        if (!o.acrossStroke.isZero()) {
            // Across the stroke, and the depth unless the depth is left to the model: rows
            // orthonormal because acrossStroke lies in the view plane.
            c.rows = o.viewPlaneOnly ? 1 : 2;
            c.A.row(0) = o.acrossStroke.transpose();
            c.A.row(1) = axis.transpose();
            c.A.row(2).setZero();
            if (c.rows == 1)
                c.A.row(1).setZero();
            c.b = c.A * o.position;
            c.noise << planeVariance, depthVariance, 0.0;
        } else if (o.viewPlaneOnly) {
            c.rows = 2;
            c.A.topRows<2>() = P;
            c.b.head<2>() = P * o.position;
            c.noise << planeVariance, planeVariance, 0.0;
        } else if (hasView && (planeVariance > 0 || depthVariance > 0)) {
            // In the view's frame, so that the depth row can carry its own noise.
            c.rows = 3;
            c.A.topRows<2>() = P;
            c.A.row(2) = axis.transpose();
            c.b = c.A * o.position;
            c.noise << planeVariance, planeVariance, depthVariance;
        } else {
            c.rows = 3;
            c.A = Eigen::Matrix3d::Identity();
            c.b = o.position;
            c.noise.setConstant(planeVariance);
        }
        added.push_back({ o.vertex, c });
    }
    if (options.mirror) {
        const MirrorMap& m = *options.mirror;
        const Eigen::Matrix3d S = m.reflection();
        const Eigen::Vector3d d = m.offset();
        const size_t own = added.size();
        for (size_t i = 0; i < own; ++i) {
            const std::uint32_t target = m.partner(added[i].first);
            if (target == MirrorMap::kNone || seen.count(target))
                continue;
            // A x = b for x, and x' = S x + d its mirror image: (A S) x' = b + A S d.
            VertexConstraint c = added[i].second;
            const Eigen::Matrix3d AS = c.A * S;
            c.b += AS * d;
            c.A = AS;
            c.viewAxis = S * axis;
            c.mirrored = true;
            seen.insert(target);
            added.push_back({ target, c });
        }
    }

    // Step 1: supersede older constraints of similar views on the vertices the stroke maps to
    // and near the line it drew (its projected points; the mapped vertices for a reading
    // without them), measured in the stroke's view plane: what the user drew over.
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> drawn; // segments, world mm
    if (reading.worldPoints.size() >= 2 && reading.worldPoints.front().allFinite()) {
        for (size_t k = 1; k < reading.worldPoints.size(); ++k)
            if (reading.worldPoints[k].allFinite() && reading.worldPoints[k - 1].allFinite())
                drawn.push_back({ reading.worldPoints[k - 1], reading.worldPoints[k] });
    } else {
        for (const VertexObservation& o : reading.observations)
            drawn.push_back({ next.face.segment<3>(3 * o.vertex), next.face.segment<3>(3 * o.vertex) });
    }
    if (options.mirror) {
        const size_t own = drawn.size();
        for (size_t k = 0; k < own; ++k)
            drawn.push_back({ options.mirror->mirror(drawn[k].first), options.mirror->mirror(drawn[k].second) });
    }
    // Distances in the view plane (in 3D for a reading without a view).
    const Eigen::Matrix3d measure = hasView ? Eigen::Matrix3d(P.transpose() * P) : Eigen::Matrix3d::Identity();
    // Each segment's start, measured direction and its squared length, once: the test below
    // runs for every constrained vertex against every segment.
    struct Segment {
        Eigen::Vector3d a, d;
        double dd;
    };
    std::vector<Segment> segments;
    segments.reserve(drawn.size());
    for (const auto& [a, b] : drawn) {
        const Eigen::Vector3d d = measure * (b - a);
        segments.push_back({ a, d, d.squaredNorm() });
    }
    auto nearDrawn = [&](const Eigen::Vector3d& x) {
        for (const Segment& s : segments) {
            const Eigen::Vector3d q = measure * (x - s.a);
            const double t = s.dd > 0 ? std::clamp(q.dot(s.d) / s.dd, 0.0, 1.0) : 0.0;
            if ((q - t * s.d).norm() <= options_.supersedeRadius)
                return true;
        }
        return false;
    };
    std::vector<bool> mapsTo(next.constraints.size(), false);
    for (const auto& [v, c] : added)
        mapsTo[v] = true;
    for (size_t v = 0; v < next.constraints.size(); ++v) {
        auto& list = next.constraints[v];
        if (list.empty() || !(mapsTo[v] || nearDrawn(next.face.segment<3>(3 * static_cast<Eigen::Index>(v)))))
            continue;
        std::erase_if(list, [&](const VertexConstraint& c) {
            // A 3D constraint (or a stroke without a view) has no view to combine with.
            return !hasView || c.rows == 3 || c.viewAxis.dot(axis) >= cosLimit;
        });
    }
    // Step 2: add the new constraints. A vertex keeps one constraint per stroke.
    for (const auto& [v, c] : added)
        next.constraints[v].push_back(c);

    // Step 3: rebuild, reweighting noisy rows that the rebuilt face leaves far behind.
    stats::ReconstructOptions ro;
    ro.cleanUp = options_.cleanUp;
    ro.correlation = options.correlation ? options_.correlation : stats::Correlation::Off;
    // The passes before the last need the face only at the constrained vertices, where the
    // joint model's conditional mean gives it without rebuilding the whole face
    // (stats::reconstructAt).
    // Without passes the constraints are used as they are, not copied.
    std::vector<std::vector<VertexConstraint>> weighted;
    if (options_.robustPasses > 0)
        weighted = next.constraints;
    const std::vector<std::vector<VertexConstraint>>& used = options_.robustPasses > 0 ? weighted : next.constraints;
    std::vector<int> constrained, slot(used.size(), -1);
    for (size_t v = 0; v < used.size(); ++v)
        if (!used[v].empty()) {
            slot[v] = static_cast<int>(constrained.size());
            constrained.push_back(static_cast<int>(v));
        }
    for (int pass = 0;; ++pass) {
        stats::Observations obs;
        for (size_t v = 0; v < used.size(); ++v)
            addCombined(obs, static_cast<Eigen::Index>(v), used[v]);
        if (pass == options_.robustPasses) {
            next.face = stats::reconstruct(model_, obs, ro).face;
            if (!next.face.allFinite())
                fail("tracking: the face model returned a non-finite face for this stroke");
            break;
        }
        const Eigen::VectorXd at = stats::reconstructAt(model_, obs, constrained, ro);
        if (!at.allFinite())
            fail("tracking: the face model returned a non-finite face for this stroke");
        for (size_t v = 0; v < weighted.size(); ++v)
            for (size_t k = 0; k < weighted[v].size(); ++k) {
                const VertexConstraint& c = next.constraints[v][k];
                const Eigen::Vector3d r = c.A * at.segment<3>(3 * slot[v]) - c.b;
                for (int i = 0; i < c.rows; ++i)
                    if (c.noise[i] > 0.0) {
                        // Huber's weight: 1 within robustK sigma, falling as 1 / residual beyond.
                        const double z = std::abs(r[i]) / std::sqrt(c.noise[i]);
                        weighted[v][k].noise[i] = z <= options_.robustK ? c.noise[i] : c.noise[i] * z / options_.robustK;
                    }
            }
    }

    // Step 4: project the constraints onto the face space.
    // Rows with noise keep their measured values: the face does not pass through them, and
    // replacing them by it after every stroke would let each stroke pull them towards the
    // prior, until many strokes later they said little of what was drawn.
    if (options_.projectOntoFaceSpace)
        for (size_t v = 0; v < next.constraints.size(); ++v)
            for (VertexConstraint& c : next.constraints[v]) {
                const Eigen::Vector3d onFace = c.A * next.face.segment<3>(3 * static_cast<Eigen::Index>(v));
                for (int i = 0; i < c.rows; ++i)
                    if (c.noise[i] == 0.0)
                        c.b[i] = onFace[i];
            }

    history_.resize(current_ + 1);
    history_.push_back(std::move(next));
    current_ = history_.size() - 1;
}

bool TrackingModel::undo()
{
    if (current_ == 0)
        return false;
    --current_;
    return true;
}

bool TrackingModel::redo()
{
    if (current_ + 1 >= history_.size())
        return false;
    ++current_;
    return true;
}

} // namespace facesketch::sketch

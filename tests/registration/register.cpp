// Tests of registration/register: the template onto an affine copy of itself, onto a scan of
// another topology with a feature the landmarks cannot know, with a hole, by both routes; and bad
// input.
#include "registration/register.h"

#include "core/error.h"
#include "registration/error_map.h"
#include "registration/surface_query.h"
#include "test_head.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace facesketch;
using namespace facesketch::registration;

namespace {

Eigen::Matrix3d someAffine()
{
    Eigen::Matrix3d M = Eigen::AngleAxisd(0.25, Eigen::Vector3d(0.3, 1, -0.2).normalized()).toRotationMatrix() * 1.1;
    M(0, 1) += 0.05;
    M(2, 0) -= 0.04;
    return M;
}

// The vertices of the face region: in front of the ears and between the brow and the chin.
std::vector<int> faceVertices(const Mesh& templ)
{
    std::vector<int> out;
    for (Eigen::Index i = 0; i < templ.V.rows(); ++i) {
        const Eigen::Vector3d u = templ.V.row(i).normalized();
        if (u.z() > 0.5 && std::abs(u.y()) < 0.6)
            out.push_back(static_cast<int>(i));
    }
    return out;
}

struct Distances {
    double mean = 0.0, max = 0.0;
};

Distances distances(const Vertices& V, const std::vector<int>& rows, const SurfaceQuery& surface)
{
    Distances d;
    for (const int v : rows) {
        const double e = surface.closest(V.row(v).transpose()).distance;
        d.mean += e / static_cast<double>(rows.size());
        d.max = std::max(d.max, e);
    }
    return d;
}

// A coarse template head and a finer scan of another topology with a cheek bump the landmarks do
// not see, the scan's surface for distances, and the template's face-region vertices.
struct CheekScan {
    static constexpr double cheek = 8.0;
    Mesh templ = test::makeHead(3);
    FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    Mesh scan = test::makeHead(5, cheek);
    FeaturePoints scanPoints = test::headPoints(cheek);
    SurfaceQuery surface { scan };
    std::vector<int> face = faceVertices(templ);
};

} // namespace

TEST_CASE("registerScan: the template onto an affine copy of itself gives back that copy")
{
    const Mesh templ = test::makeHead(3);
    const FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    const Eigen::Matrix3d M = someAffine();
    const Eigen::RowVector3d t(10, -20, 35);
    Mesh scan = templ;
    scan.V = (templ.V * M.transpose()).rowwise() + t;
    FeaturePoints scanPoints;
    for (const auto& [name, p] : templPoints)
        scanPoints[name] = M * p + t.transpose();
    for (const auto method : { RegistrationMethod::DepthMaps, RegistrationMethod::Projection }) {
        RegistrationOptions options;
        options.method = method;
        options.mapWidth = options.mapHeight = 256;
        const Registration r = registerScan(templ, templPoints, scan, scanPoints, "copy.ply", options);
        INFO("method " << static_cast<int>(method));
        REQUIRE(r.points.estimated.empty());
        REQUIRE((r.approximation - scan.V).rowwise().norm().maxCoeff() < 1e-6);
        REQUIRE((r.registered - scan.V).rowwise().norm().maxCoeff() < 0.05);
        const auto scanned = std::count(r.source.begin(), r.source.end(), VertexSource::Scan);
        REQUIRE(scanned > templ.V.rows() / 2);
    }
}

TEST_CASE("registerScan: moves the approximation onto a scan of another topology, both routes")
{
    const CheekScan c;
    const Mesh& templ = c.templ;
    const FeaturePoints& templPoints = c.templPoints;
    const Mesh& scan = c.scan;
    const FeaturePoints& scanPoints = c.scanPoints;
    const SurfaceQuery& surface = c.surface;
    const std::vector<int>& face = c.face;
    for (const auto method : { RegistrationMethod::DepthMaps, RegistrationMethod::Projection }) {
        RegistrationOptions options;
        options.method = method;
        options.mapWidth = options.mapHeight = 256;
        options.refinePasses = 0; // the thesis' single pass: its approximation is the landmarks' RBF alone
        const Registration r = registerScan(templ, templPoints, scan, scanPoints, "scan.ply", options);
        const Distances before = distances(r.approximation, face, surface);
        const Distances after = distances(r.registered, face, surface);
        INFO("method " << static_cast<int>(method) << ": approximation mean " << before.mean << " max " << before.max
                       << ", registered mean " << after.mean << " max " << after.max);
        REQUIRE(before.max > 3.0); // the RBF alone misses the cheek
        REQUIRE(after.mean < 0.02);
        REQUIRE(after.max < 0.15);
    }
    // Reading the map between pixel centres instead of on the scan's triangle leaves the coarse
    // template's creases in: worse at the nose tip, still far better than the approximation.
    for (const auto readBack : { ReadBack::Bilinear, ReadBack::Thesis }) {
        RegistrationOptions options;
        options.readBack = readBack;
        options.mapWidth = options.mapHeight = 256;
        const Registration r = registerScan(templ, templPoints, scan, scanPoints, "scan.ply", options);
        const Distances after = distances(r.registered, face, surface);
        INFO("read back " << static_cast<int>(readBack) << ": registered mean " << after.mean << " max " << after.max);
        REQUIRE(after.mean < 0.1);
        REQUIRE(after.max > 0.15);
        REQUIRE(after.max < 1.0);
    }
}

TEST_CASE("registerScan: a hole in the scan keeps the approximation there, labelled, with a blended seam")
{
    const Mesh templ = test::makeHead(4);
    const FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    const double cheek = 8.0;
    const Mesh full = test::makeHead(5, cheek);
    // Cut the cheek out: drop every triangle whose centroid's direction is within 0.2 of the bump.
    const Eigen::Vector3d bump = Eigen::Vector3d(0.45, -0.2, 0.87).normalized();
    std::vector<int> kept;
    for (Eigen::Index f = 0; f < full.F.rows(); ++f) {
        const Eigen::Vector3d c = (full.V.row(full.F(f, 0)) + full.V.row(full.F(f, 1)) + full.V.row(full.F(f, 2))).normalized();
        if ((c - bump).norm() > 0.2)
            kept.push_back(static_cast<int>(f));
    }
    Mesh scan;
    scan.V = full.V;
    scan.F.resize(static_cast<Eigen::Index>(kept.size()), 3);
    for (std::size_t i = 0; i < kept.size(); ++i)
        scan.F.row(static_cast<Eigen::Index>(i)) = full.F.row(kept[i]);
    RegistrationOptions options;
    options.mapWidth = options.mapHeight = 256;
    options.blendPixels = 3.0; // about 6 mm here: the hole (about 16 mm across) keeps a middle
    const Registration r = registerScan(templ, templPoints, scan, test::headPoints(cheek), "holed.ply", options);
    int inHole = 0, blended = 0;
    for (Eigen::Index v = 0; v < templ.V.rows(); ++v) {
        const Eigen::Vector3d u = templ.V.row(v).normalized();
        const double away = (u - bump).norm();
        if (away < 0.08) { // well inside the hole
            REQUIRE(r.source[static_cast<std::size_t>(v)] == VertexSource::Approximation);
            REQUIRE((r.registered.row(v) - r.approximation.row(v)).norm() == 0.0);
            ++inHole;
        }
        if (r.source[static_cast<std::size_t>(v)] == VertexSource::Blended)
            ++blended;
    }
    REQUIRE(inHole >= 3);
    REQUIRE(blended >= 3);
    // Away from the hole the scan is followed as before.
    const SurfaceQuery surface(scan);
    const std::vector<double> error = distanceToSurface(r.registered, surface);
    for (Eigen::Index v = 0; v < templ.V.rows(); ++v)
        if (r.source[static_cast<std::size_t>(v)] == VertexSource::Scan && templ.V.row(v).normalized().z() > 0.5)
            REQUIRE(error[static_cast<std::size_t>(v)] < 0.3);
}

TEST_CASE("registerScan: a mask without ears registers from its points, the ears estimated")
{
    const Mesh templ = test::makeHead(3);
    const FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    const Mesh scan = test::makeHead(4, 5.0);
    FeaturePoints points = test::headPoints(5.0);
    points.erase("obs_l");
    points.erase("obs_r");
    RegistrationOptions options;
    options.mapWidth = options.mapHeight = 128;
    const Registration r = registerScan(templ, templPoints, scan, points, "mask.ply", options);
    REQUIRE(r.points.estimated == std::vector<std::string> { "obs_l", "obs_r" });
    const SurfaceQuery surface(scan);
    REQUIRE(distances(r.registered, faceVertices(templ), surface).mean < 0.1);
}

TEST_CASE("registerScan: bad scans and options name the scan")
{
    const Mesh templ = test::makeHead(2);
    const FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    const FeaturePoints points = test::headPoints();
    REQUIRE_THROWS_WITH(
        registerScan(templ, templPoints, Mesh {}, points, "empty.ply"), Catch::Contains("empty.ply: the scan has no triangles"));
    Mesh nan = test::makeHead(2);
    nan.V(5, 1) = std::nan("");
    REQUIRE_THROWS_WITH(registerScan(templ, templPoints, nan, points, "nan.ply"), Catch::Contains("nan.ply"));
    RegistrationOptions bad;
    bad.smoothing = 1.5;
    REQUIRE_THROWS_WITH(
        registerScan(templ, templPoints, templ, points, "s.ply", bad), Catch::Contains("s.ply: smoothing 1.5 outside [0, 1]"));
    RegistrationOptions passes;
    passes.refinePasses = 5;
    REQUIRE_THROWS_WITH(
        registerScan(templ, templPoints, templ, points, "p.ply", passes), Catch::Contains("p.ply: refinement passes 5 outside [0, 4]"));
    RegistrationOptions spacing;
    spacing.refineSpacing = 0.0;
    REQUIRE_THROWS_WITH(registerScan(templ, templPoints, templ, points, "q.ply", spacing), Catch::Contains("q.ply: refinement passes 1"));
    RegistrationOptions steps;
    steps.smoothingSteps = -1;
    REQUIRE_THROWS_WITH(registerScan(templ, templPoints, templ, points, "d.ply", steps),
        Catch::Contains("d.ply: displacement smoothing steps -1 outside [0, 100]"));
    REQUIRE_THROWS_WITH(landmarkPositions(templ, { { "prn", 100000 } }), Catch::Contains("template landmark 'prn': vertex 100000"));
}

TEST_CASE("registerScan: only the chosen vertex range is registered, the rest keeps the approximation")
{
    const Mesh templ = test::makeHead(3);
    const FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    const Mesh scan = test::makeHead(4, 8.0);
    RegistrationOptions options;
    options.mapWidth = options.mapHeight = 128;
    options.firstVertex = 100;
    options.endVertex = 400;
    const Registration r = registerScan(templ, templPoints, scan, test::headPoints(8.0), "scan.ply", options);
    int moved = 0;
    for (Eigen::Index v = 0; v < templ.V.rows(); ++v) {
        const bool inside = v >= 100 && v < 400;
        if (!inside) {
            REQUIRE(r.source[static_cast<std::size_t>(v)] == VertexSource::Approximation);
            REQUIRE(r.registered.row(v) == r.approximation.row(v));
        } else if ((r.registered.row(v) - r.approximation.row(v)).norm() > 1e-6) {
            ++moved;
        }
    }
    REQUIRE(moved > 20);
    options.endVertex = 5000;
    REQUIRE_THROWS_WITH(registerScan(templ, templPoints, scan, test::headPoints(8.0), "scan.ply", options),
        Catch::Contains("registered vertices [100, 5000)"));
}

TEST_CASE("registerScan: the scan is used only between the ears unless told otherwise")
{
    const Mesh templ = test::makeHead(3);
    const FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    // A scan 2 mm larger all round, so every vertex that uses it moves.
    Mesh scan = test::makeHead(4);
    scan.V *= 1.02;
    FeaturePoints points;
    for (const auto& [name, p] : test::headPoints())
        points[name] = 1.02 * p;
    for (const bool betweenEars : { true, false }) {
        RegistrationOptions options;
        options.mapWidth = options.mapHeight = 128;
        options.betweenEars = betweenEars;
        // One pass: a refinement moves the head behind the ears too, by the RBF refitted on the
        // face (tested below).
        options.refinePasses = 0;
        const Registration r = registerScan(templ, templPoints, scan, points, "scan.ply", options);
        const double earL = r.frame.toCylinder(points.at("obs_l"))(0), earR = r.frame.toCylinder(points.at("obs_r"))(0);
        const double blend = (options.blendPixels + 1.5) * r.grid.dTheta(); // the seam blend, in radians
        int behind = 0, behindMoved = 0;
        for (Eigen::Index v = 0; v < templ.V.rows(); ++v) {
            const Eigen::Vector3d thr = r.frame.toCylinder(r.approximation.row(v).transpose());
            // Well behind the ears, beyond the blend, and away from the poles.
            if ((thr(0) > earL + blend || thr(0) < earR - blend) && std::abs(thr(1)) < 40.0) {
                ++behind;
                if ((r.registered.row(v) - r.approximation.row(v)).norm() > 1e-6)
                    ++behindMoved;
            }
        }
        INFO("between ears " << betweenEars << ": " << behindMoved << " of " << behind << " vertices behind the ears moved");
        REQUIRE(behind > 20);
        if (betweenEars)
            REQUIRE(behindMoved == 0);
        else
            REQUIRE(behindMoved > behind / 2);
    }
}

TEST_CASE("registerScan: a fin the rays graze (a scanning artefact under the jaw) leaves no spikes")
{
    const Mesh templ = test::makeHead(4);
    const FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    const Mesh head = test::makeHead(4);
    // A horizontal fin 8 mm wide round the head at y = -70 mm, such as a scanner leaves at an
    // occluding edge: seen from the axis, its triangles are edge-on slivers.
    const double y = -70.0, scale = std::sqrt(1.0 - (y / 90.0) * (y / 90.0));
    const int steps = 96;
    Mesh scan;
    scan.V.resize(head.V.rows() + 2 * steps, 3);
    scan.V.topRows(head.V.rows()) = head.V;
    scan.F.resize(head.F.rows() + 2 * steps, 3);
    scan.F.topRows(head.F.rows()) = head.F;
    const int base = static_cast<int>(head.V.rows());
    for (int i = 0; i < steps; ++i) {
        const double phi = 2.0 * std::numbers::pi * i / steps;
        const Eigen::Vector3d inner(0.99 * 70.0 * scale * std::sin(phi), y, 0.99 * 80.0 * scale * std::cos(phi));
        Eigen::Vector3d radial(inner.x(), 0.0, inner.z());
        radial.normalize();
        scan.V.row(base + 2 * i) = inner.transpose();
        scan.V.row(base + 2 * i + 1) = (inner + 8.0 * radial).transpose();
        const int a = base + 2 * i, b = base + 2 * ((i + 1) % steps);
        scan.F.row(head.F.rows() + 2 * i) << a, b, a + 1;
        scan.F.row(head.F.rows() + 2 * i + 1) << b, b + 1, a + 1;
    }
    const SurfaceQuery skin(head);
    auto worst = [&](double grazingCosine, int refinePasses) {
        RegistrationOptions options;
        options.mapWidth = options.mapHeight = 256;
        options.grazingCosine = grazingCosine;
        options.refinePasses = refinePasses;
        const Registration r = registerScan(templ, templPoints, scan, test::headPoints(), "fin.ply", options);
        double most = 0.0; // the farthest registered vertex from the skin, near the fin, in front
        for (Eigen::Index v = 0; v < templ.V.rows(); ++v)
            if (std::abs(templ.V(v, 1) - y) < 10.0 && templ.V(v, 2) > 20.0)
                most = std::max(most, skin.closest(r.registered.row(v).transpose()).distance);
        return most;
    };
    // In one pass (the thesis), the fin pulls front vertices off the skin unless repaired; the
    // default refinement must not bring the spikes back.
    const double off = worst(0.0, 0), on = worst(RegistrationOptions {}.grazingCosine, 0);
    const double refined = worst(RegistrationOptions {}.grazingCosine, RegistrationOptions {}.refinePasses);
    INFO("farthest vertex from the skin near the fin: " << off << " mm without the repair, " << on << " mm with it, " << refined
                                                        << " mm with it and the default refinement");
    REQUIRE(off > 2.0);
    REQUIRE(on < 0.5);
    REQUIRE(refined < 0.5);
}

TEST_CASE("registerScan: a refinement pass refits the RBF on the first pass's scan vertices")
{
    const CheekScan c;
    const Mesh& templ = c.templ;
    const FeaturePoints& templPoints = c.templPoints;
    const Mesh& scan = c.scan;
    const FeaturePoints& scanPoints = c.scanPoints;
    const SurfaceQuery& surface = c.surface;
    const std::vector<int>& face = c.face;
    RegistrationOptions options;
    options.mapWidth = options.mapHeight = 256;
    options.refinePasses = 0;
    const Registration single = registerScan(templ, templPoints, scan, scanPoints, "scan.ply", options);
    options.refinePasses = 1;
    const Registration refined = registerScan(templ, templPoints, scan, scanPoints, "scan.ply", options);
    const Distances before = distances(single.approximation, face, surface), after = distances(refined.approximation, face, surface);
    const Distances registered = distances(refined.registered, face, surface);
    INFO("approximation to scan: mean " << before.mean << " max " << before.max << " in one pass, mean " << after.mean << " max "
                                        << after.max << " refined with " << refined.refinementPoints << " points; registered mean "
                                        << registered.mean << " max " << registered.max);
    REQUIRE(single.refinementPoints == 0);
    // Points refineSpacing apart over the scanned part of a head of radius 70-90 mm: dozens.
    REQUIRE(refined.refinementPoints > 20);
    REQUIRE(after.mean < before.mean / 3.0);
    REQUIRE(after.max < before.max / 2.0);
    REQUIRE(registered.mean < 0.02);
    REQUIRE(registered.max < 0.15);
    // The refined RBF still interpolates the feature points: each landmark vertex lands on its point.
    for (const auto& [name, vertex] : test::headLandmarks(templ))
        REQUIRE((refined.approximation.row(vertex).transpose() - scanPoints.at(name)).norm() < 1e-6);
}

TEST_CASE("registerScan: smoothing the displacement averages the scan's noise")
{
    const Mesh templ = test::makeHead(4);
    const FeaturePoints templPoints = landmarkPositions(templ, test::headLandmarks(templ));
    const Eigen::Matrix3d M = someAffine();
    const Eigen::RowVector3d t(10, -20, 35);
    Mesh truth = templ;
    truth.V = (templ.V * M.transpose()).rowwise() + t;
    // The scan: the same surface, 0.3 mm of seeded noise on every vertex.
    Mesh scan = truth;
    std::uint32_t state = 12345;
    auto uniform = [&state] {
        state = state * 1664525u + 1013904223u;
        return static_cast<double>(state >> 8) / static_cast<double>(1u << 24) - 0.5;
    };
    for (Eigen::Index v = 0; v < scan.V.rows(); ++v)
        for (int k = 0; k < 3; ++k)
            scan.V(v, k) += 0.3 * std::sqrt(12.0) * uniform();
    FeaturePoints scanPoints;
    for (const auto& [name, p] : templPoints)
        scanPoints[name] = M * p + t.transpose();
    const SurfaceQuery surface(truth);
    const std::vector<int> face = faceVertices(templ);
    auto error = [&](int steps) {
        RegistrationOptions options;
        options.mapWidth = options.mapHeight = 256;
        options.smoothingSteps = steps;
        return distances(registerScan(templ, templPoints, scan, scanPoints, "noisy.ply", options).registered, face, surface);
    };
    const Distances raw = error(0), smoothed = error(3);
    INFO("to the noise-free surface: mean " << raw.mean << " max " << raw.max << " unsmoothed, mean " << smoothed.mean << " max "
                                            << smoothed.max << " after 3 steps");
    REQUIRE(raw.mean > 0.1); // the registered face lies on the noisy scan
    REQUIRE(smoothed.mean < 0.7 * raw.mean);
}

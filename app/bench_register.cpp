// `facesketch bench register`: seconds to register one scan (issue 15 goal: under 2 s at 6,000
// template vertices and a 100,000-triangle scan), by depth maps and by projection.
#include "bench.h"

#include "core/stopwatch.h"
#include "geometry/primitives.h"
#include "registration/register.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace facesketch::app {

namespace {

using namespace facesketch::registration;

// An analytic head: ellipsoid (70, 90, 80 mm) with a nose, plus `cheek` mm of a bump on the left
// cheek, as a function of the unit direction u.
Eigen::Vector3d head(const Eigen::Vector3d& u, double cheek)
{
    const double nose = 12.0 * std::exp(-(u.x() * u.x() + (u.y() + 0.1) * (u.y() + 0.1)) / 0.02) * std::max(0.0, u.z());
    const double bump = cheek * std::exp(-((u.x() - 0.45) * (u.x() - 0.45) + (u.y() + 0.2) * (u.y() + 0.2)) / 0.03) * std::max(0.0, u.z());
    return Eigen::Vector3d(70.0 * u.x(), 90.0 * u.y(), 80.0 * u.z()) + (nose + bump) * u;
}

Eigen::Vector3d direction(double azimuth, double elevation)
{
    return { std::sin(azimuth) * std::cos(elevation), std::sin(elevation), std::cos(azimuth) * std::cos(elevation) };
}

// A face mask: an n by n grid over azimuth [-halfWidth, halfWidth] and elevation [-1, 0.9] rad
// mapped onto the head; triangles turned to face outward.
Mesh mask(int n, double halfWidth, double cheek, double noise, std::mt19937_64& rng)
{
    Mesh mesh = makeGrid(n, n, 2.0, 2.0);
    std::normal_distribution<double> gauss(0.0, noise);
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
        const Eigen::Vector3d p = head(direction(mesh.V(v, 0) * halfWidth, 0.95 * mesh.V(v, 1) - 0.05), cheek);
        mesh.V.row(v) = (p + Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)) * (noise > 0.0 ? 1.0 : 0.0)).transpose();
    }
    return mesh;
}

FeaturePoints points(double cheek)
{
    FeaturePoints p;
    auto add = [&](const char* name, double x, double y, double z) { p[name] = head(Eigen::Vector3d(x, y, z).normalized(), cheek); };
    add("prn", 0.0, -0.1, 1.0);
    add("sn", 0.0, -0.3, 1.0);
    add("en_l", 0.15, 0.2, 1.0);
    add("en_r", -0.15, 0.2, 1.0);
    add("ex_l", 0.45, 0.2, 1.0);
    add("ex_r", -0.45, 0.2, 1.0);
    add("ch_l", 0.3, -0.5, 1.0);
    add("ch_r", -0.3, -0.5, 1.0);
    add("pg", 0.0, -0.85, 1.0);
    add("n", 0.0, 0.3, 1.0);
    add("ls", 0.0, -0.42, 1.0);
    add("li", 0.0, -0.6, 1.0);
    return p;
}

} // namespace

void benchRegister(const BenchOptions& options, std::ostream& out)
{
    std::mt19937_64 rng(15);
    const int side = std::max(8, static_cast<int>(std::lround(std::sqrt(double(options.vertices)))));
    const Mesh templ = mask(side, 1.4, 0.0, 0.0, rng);
    const Mesh scan = mask(224, 1.3, 6.0, 0.2, rng); // 99,458 triangles
    out << "# template: " << templ.V.rows() << " vertices; scan: " << scan.F.rows() << " triangles, 0.2 mm noise; 512 x 512 maps\n";
    // The template's feature points on its own surface (its nearest vertices would do as well).
    const FeaturePoints templPoints = points(0.0);
    const FeaturePoints scanPoints = points(6.0);
    for (const auto method : { RegistrationMethod::DepthMaps, RegistrationMethod::Projection }) {
        RegistrationOptions o;
        o.method = method;
        std::vector<double> seconds;
        long fromScan = 0;
        for (int i = 0; i < std::max(1, options.repeat / 5); ++i) {
            const Stopwatch clock;
            const Registration r = registerScan(templ, templPoints, scan, scanPoints, "bench scan", o);
            seconds.push_back(clock.seconds());
            fromScan = std::count(r.source.begin(), r.source.end(), VertexSource::Scan);
        }
        out << "# " << fromScan << " of " << templ.V.rows() << " vertices registered from the scan\n";
        out << (method == RegistrationMethod::DepthMaps ? "register_depth_maps_s " : "register_projection_s ") << median(seconds) << " s\n";
    }
}

} // namespace facesketch::app

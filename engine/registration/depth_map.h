#pragma once
// Cylindrical unwrapping and depth maps (thesis 3.2.11, 3.2.12.1).
//
// A CylinderFrame is a vertical axis through the head: `up` along the axis, `right` toward the
// face's left (+x of docs/conventions.md) and `forward` the way the face looks. A point p has
// cylindrical coordinates (theta, h, r): h = up . (p - origin) along the axis, r its distance
// from the axis (the "depth"), and theta = atan2(right . d, forward . d) of its radial part d,
// so theta = 0 straight ahead, +pi/2 at the face's left ear, +-pi behind the head (the seam).
//
// A DepthMap is a width x height grid laid over [thetaMin, thetaMax] x [hMin, hMax]: pixel
// (x, y) (x to the right, y down, (0, 0) top-left) covers theta in thetaMin + [x, x + 1] *
// dTheta and h in hMax - [y, y + 1] * dH, and stores the depth r at its centre, interpolated
// with barycentric coordinates over the unwrapped triangle covering the centre (eq. 3.8). Where
// several triangles cover it the largest r wins (the outermost surface, thesis 3.2.12), and
// the winning triangle is recorded. Triangles that straddle the seam are skipped.

#include "core/mesh.h"

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

namespace facesketch::registration {

struct CylinderFrame {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    Eigen::Vector3d right = Eigen::Vector3d::UnitX();
    Eigen::Vector3d up = Eigen::Vector3d::UnitY();
    Eigen::Vector3d forward = Eigen::Vector3d::UnitZ();

    /// (theta, h, r) of p.
    Eigen::Vector3d toCylinder(const Eigen::Vector3d& p) const;
    /// The point at (theta, h, r).
    Eigen::Vector3d fromCylinder(const Eigen::Vector3d& thr) const;
    /// Every row of V in cylindrical coordinates, #V by 3 (theta, h, r).
    Vertices unwrap(const Vertices& V) const;
};

/// The frame fixed by the feature points of a face (mm, any pose): up from the mouth corners'
/// midpoint to the eye corners' midpoint, right from ex_r to ex_l made orthogonal to up, forward
/// = right x up; the axis passes through the ears' midpoint (obs_l, obs_r) or, without them, one
/// eye width (|ex_l - ex_r|) behind the eye corners. Needs ex_l, ex_r, ch_l, ch_r; throws Error
/// naming the missing one or a degenerate configuration.
CylinderFrame frameFromFeaturePoints(const std::vector<std::string>& names, const Vertices& points);

/// Pixel grid of a depth map over cylindrical coordinates.
struct DepthGrid {
    int width = 512, height = 512;
    double thetaMin = -3.14159265358979, thetaMax = 3.14159265358979;
    double hMin = -100.0, hMax = 100.0; ///< mm along the axis

    double dTheta() const { return (thetaMax - thetaMin) / width; }
    double dH() const { return (hMax - hMin) / height; }
    /// Continuous pixel coordinates of (theta, h): pixel (x, y)'s centre is at (x + 0.5, y + 0.5).
    Eigen::Vector2d toPixel(double theta, double h) const { return { (theta - thetaMin) / dTheta(), (hMax - h) / dH() }; }
    /// (theta, h) of the centre of pixel (x, y).
    Eigen::Vector2d centre(int x, int y) const { return { thetaMin + (x + 0.5) * dTheta(), hMax - (y + 0.5) * dH() }; }
};

/// The grid covering unwrapped points (#V by 3 of theta, h, r) with `marginPixels` to spare on
/// each side, theta clamped to [-pi, pi].
DepthGrid gridAround(const Vertices& unwrapped, int width, int height, double marginPixels = 2.0);

struct DepthMap {
    DepthGrid grid;
    std::vector<double> depth; ///< width*height, row-major from the top; NaN where no triangle
    std::vector<int> triangle; ///< the triangle whose depth the pixel holds, -1 where none

    bool valid(int x, int y) const { return !std::isnan(at(x, y)); }
    double at(int x, int y) const { return depth[static_cast<std::size_t>(y) * grid.width + x]; }
};

/// Rasterises an unwrapped mesh. @param[in] unwrapped  #V by 3 (theta, h, r); F its triangles.
DepthMap rasterizeDepth(const Vertices& unwrapped, const Triangles& F, const DepthGrid& grid);

/// Bilinear interpolation of a width x height field (row-major, pixel centres at +0.5) at
/// continuous pixel coordinates; coordinates are clamped to the grid. NaN if a used neighbour is
/// NaN.
double sampleBilinear(const std::vector<double>& field, int width, int height, const Eigen::Vector2d& pixel);

} // namespace facesketch::registration

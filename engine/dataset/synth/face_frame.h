#pragma once
// Internal to engine/dataset/synth: the per-face frame of the synthetic face generator (face_generator.h),
// i.e. everything derived from FaceParams once per face (landmark targets, the midline
// profile, head widths, eyeballs, the grid's knot angles), and small shared helpers.
// face_frame.cpp builds it; face_shape.cpp evaluates vertices with it.

#include "core/error.h"
#include "dataset/synth/face_generator.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace facesketch::dataset::detail {

// Where each nostril opens on the nose's underside: kNostrilAt of the way from sn up to prn and
// kNostrilOut of the way from the midline out to al. face_shape.cpp centres the nostril's
// vestibule (and the dimple's height) there; face_topology.cpp rings that point with the
// labelled nostril contour and hides the vertices inside it.
constexpr double kNostrilAt = 0.4;
constexpr double kNostrilOut = 0.4;
// The opening's footprint (face_shape.cpp vestibule()): kNostrilHalfHeight of sn..prn tall and
// kNostrilHalfWidth nostril sizes wide (half-axes). With the population's mean nostril size and
// al-al (4.2 and 33.1 mm) the half-width is 0.30 of the way out to al: face_topology.cpp puts the
// labelled nostril ring that far from the centre, on the opening's rim.
constexpr double kNostrilHalfHeight = 0.35;
constexpr double kNostrilHalfWidth = 1.2;
constexpr double kNostrilHalfWidthOfAl = 0.30;

// The subnasal ridge (v20): the columella's base and the top of the philtrum stand forward of
// the skin lip on either side, a ridge kSubnasalRidge mm high on the midline, falling to nothing
// kSubnasalRidgeHalfWidth mm to each side (a Gaussian's scale), kSubnasalRidgeAbove mm above sn
// and kSubnasalRidgeSpread mm tall (face_shape.cpp soft()). ICT-FaceKit's mean face is such a
// ridge: at sn's height its surface falls 6 mm from the midline to 12 mm out, where v19's fell
// 0.6, so v19's midline under the nose lay 5 mm behind ICT's while 12 mm out the two agreed.
// subnasalRidge (below) gives its height. makeFrame puts sn as far forward as the ridge is high
// there (3.9 mm) and keeps the profile's knot at sn where v19 put it (the frame solves that
// knot's depth until the finished skin passes through sn, and the ridge makes up the
// difference): the ridge moves the midline, not the face beside it.
constexpr double kSubnasalRidge = 5.0;
constexpr double kSubnasalRidgeHalfWidth = 8.0;
constexpr double kSubnasalRidgeAbove = 2.0;
constexpr double kSubnasalRidgeSpread = 4.0;

inline double smoothstep(double e0, double e1, double x)
{
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}
inline double fall(double t)
{
    return 1 - smoothstep(0, 1, t);
}
inline double sq(double x)
{
    return x * x;
}
inline double lerp(double a, double b, double t)
{
    return a + (b - a) * t;
}

// C1 smooth maximum; equals max(a, b) when they differ by more than k.
inline double smax(double a, double b, double k)
{
    const double h = std::max(k - std::abs(a - b), 0.0) / k;
    return std::max(a, b) + h * h * k * 0.25;
}

/// The subnasal ridge's height (mm) at X mm from the midline and `aboveSn` mm above sn: soft()
/// adds it to the skin, makeFrame moves sn forward by its value at sn.
inline double subnasalRidge(double X, double aboveSn)
{
    return kSubnasalRidge * std::exp(-sq(X / kSubnasalRidgeHalfWidth) - sq((aboveSn - kSubnasalRidgeAbove) / kSubnasalRidgeSpread));
}

// Fritsch-Carlson monotone cubic through (x[i], y[i]), x increasing; clamped outside.
struct Monotone {
    std::vector<double> x, y, m;

    void build()
    {
        const size_t n = x.size();
        std::vector<double> d(n - 1);
        for (size_t i = 0; i + 1 < n; ++i) {
            if (!(x[i + 1] > x[i]))
                fail("synthetic face: profile knots not increasing at ", i, " (", x[i], ", ", x[i + 1], ")");
            d[i] = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
        }
        m.assign(n, 0);
        m[0] = d[0];
        m[n - 1] = d[n - 2];
        for (size_t i = 1; i + 1 < n; ++i)
            m[i] = d[i - 1] * d[i] <= 0 ? 0 : (d[i - 1] + d[i]) / 2;
        for (size_t i = 0; i + 1 < n; ++i) {
            if (d[i] == 0) {
                m[i] = m[i + 1] = 0;
                continue;
            }
            const double a = m[i] / d[i], b = m[i + 1] / d[i], s = a * a + b * b;
            if (s > 9) {
                m[i] = 3 * a / std::sqrt(s) * d[i];
                m[i + 1] = 3 * b / std::sqrt(s) * d[i];
            }
        }
    }
    double operator()(double t) const
    {
        if (t <= x.front())
            return y.front() + m.front() * (t - x.front());
        if (t >= x.back())
            return y.back() + m.back() * (t - x.back());
        const size_t i = static_cast<size_t>(std::upper_bound(x.begin(), x.end(), t) - x.begin()) - 1;
        const double h = x[i + 1] - x[i], s = (t - x[i]) / h;
        const double h00 = (1 + 2 * s) * sq(1 - s), h10 = s * sq(1 - s), h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
        return h00 * y[i] + h10 * h * m[i] + h01 * y[i + 1] + h11 * h * m[i + 1];
    }
};

// An ellipsoid with orthonormal axes: the eyeballs, and the nose's tip dome (face_shape.cpp).
struct Ellipsoid {
    Eigen::Vector3d centre, right, up, forward;
    double a = 12, b = 12, c = 12; // semi-axes along right, up, forward
};

// The nasolabial fold's centre line in the neutral face's (|x|, y) plane, mm: a quadratic Bezier
// from points.front() to points.back() as kSegments straight pieces, and the box outside which
// the fold adds nothing. The same for every vertex of a face, so makeFrame builds it once
// (nasolabialCurve()).
struct NasolabialCurve {
    static constexpr int kSegments = 32;
    Eigen::Vector2d along = Eigen::Vector2d::UnitY(); // unit chord, front to back
    double chord = 1;                                 // |back - front|
    Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();
    std::array<Eigen::Vector2d, kSegments + 1> points {};
};

// Everything derived from FaceParams that the per-vertex evaluation needs.
struct Frame {
    FaceParams p;
    Monotone depth; // horizontal depth of the midline, as a function of phi
    Monotone width; // half width at theta = 90 degrees, as a function of phi
    double yG = 19; // the glabella's height, where the profile's brow knot is (v21: 17 mm above n)
    double zf = 88, yN = 8, ySn = -46, zSn = 89, yPrn = -42, zPrn = 109, ySto = -68, zSto = 88, yGn = -112, zGn = 75, yPg = -100, zPg = 86;
    double phiTopFront = 0.8, phiBrow = 0.2, phiN = 0.1, phiPrn = -0.4, phiSn = -0.5, phiLs = -0.6, phiSto = -0.65, phiLi = -0.7,
           phiPg = -0.8, phiGn = -0.9, phiBottomFront = -1.3;
    double noseTip = 20; // radial height of the nose at prn
    // al's X on the neutral chart: half al-al less the ala's sideways swell there (alaSpread). The
    // chart's nose columns, and so the labelled nostril rings, are spaced out to it, and the
    // nostrils' footprints (face_shape.cpp) are placed on the same scale.
    double xAl = 17;
    double thetaEn = 0.2, thetaEx = 0.6, thetaAl = 0.2, thetaCh = 0.3;
    double rEye = 80;        // mm per radian near the eyes
    double rMouth = 90;      // mm per radian of azimuth near the mouth
    double mouthScale = 140; // mm per radian of elevation near the mouth (midline height)
    double xEye = 31;        // eyeball centre, base x
    Ellipsoid eye[2];        // right (-x), left (+x)
    NasolabialCurve fold;    // built before the first neutralRadius() call
};

/// Height of the base midline at elevation phi (mm): the vertical coordinate of the mouth
/// region, shared by every vertex of a grid row so lip features follow the rows.
double midY(const Frame& f, double phi);
/// Superellipse exponent of the head's horizontal sections at elevation phi.
double exponent(const Frame& f, double phi);
/// Horizontal distance from the vertical axis to the skin base (no features), mm.
double rhoBase(const Frame& f, double theta, double phi);
/// Unit direction of azimuth theta (0: +z, positive towards +x) and elevation phi (radians).
Eigen::Vector3d direction(double theta, double phi);

/// The frame of one face: targets from `p`, then the grid's knot angles solved on the skin.
Frame makeFrame(const FaceParams& p);
/// The nasolabial fold's centre line from the frame's landmark targets (al-al, ch-ch, sn, prn,
/// sto); defined in face_shape.cpp beside the fold's other constants.
NasolabialCurve nasolabialCurve(const Frame& f);
/// Skin radius of the neutral face along (theta, phi); defined in face_shape.cpp.
double neutralRadius(const Frame& f, double theta, double phi);
/// How far the vertex at (theta, phi) of the neutral chart moves sideways with its ala: outwards
/// from the midline, zero away from the alar lobule; defined in face_shape.cpp (kAlaSpread).
Eigen::Vector3d alaSpread(const Frame& f, double theta, double phi);

} // namespace facesketch::dataset::detail

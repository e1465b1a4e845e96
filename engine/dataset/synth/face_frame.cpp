// The per-face frame of the synthetic face model (face_frame.h): the landmark targets drawn
// in face_params.cpp become a midline profile through glabella, nasion, subnasale, stomion,
// pogonion and gnathion, head widths by elevation, eyeball ellipsoids and the azimuths and
// elevations at which the grid's knot rows and columns put each landmark.
//
// Sources: Farkas LG, Anthropometry of the Head and Face, 2nd ed., 1994 (the targets); the
// profile curve is the Fritsch-Carlson monotone cubic (Fritsch FN, Carlson RE, SIAM J. Numer.
// Anal. 17(2), 1980).
#include "dataset/synth/face_frame.h"

namespace facesketch::dataset::detail {

double midY(const Frame& f, double phi)
{
    return f.depth(phi) * std::tan(phi);
}

double exponent(const Frame& f, double phi)
{
    return 2.3 + (0.35 * f.p.jawAngle - 0.25) * smoothstep(-0.4, -0.9, phi);
}

// Horizontal distance from the axis of the skin base (no features) along azimuth theta.
double rhoBase(const Frame& f, double theta, double phi)
{
    const double dz = f.depth(phi), w = f.width(phi), p = exponent(f, phi);
    const double s = std::abs(std::sin(theta)), c = std::cos(theta);
    const double denom = std::pow(s / w, p) + std::pow(std::abs(c) / (c >= 0 ? dz : w), p);
    return std::pow(denom, -1.0 / p);
}

Eigen::Vector3d direction(double theta, double phi)
{
    return { std::cos(phi) * std::sin(theta), std::sin(phi), std::cos(phi) * std::cos(theta) };
}

namespace {

// The azimuth at which the neutral skin at elevation phi reaches x = target: 8 fixed-point
// steps, then secant steps, which converge where the radius changes fast with the azimuth (the
// lower nose's steep flank at al left the fixed point 0.07 mm short; issue 16).
double solveTheta(const Frame& f, double target, double phi, double start)
{
    double theta = start;
    for (int i = 0; i < 8; ++i) {
        const double r = neutralRadius(f, theta, phi) * std::cos(phi);
        theta = std::asin(std::clamp(target / r, -0.99, 0.99));
    }
    auto x = [&](double t) { return neutralRadius(f, t, phi) * std::cos(phi) * std::sin(t); };
    double prev = theta * 0.999, gPrev = x(prev) - target;
    for (int i = 0; i < 6; ++i) {
        const double g = x(theta) - target;
        if (std::abs(g) < 1e-9 || g == gPrev)
            break;
        const double next = theta - g * (theta - prev) / (g - gPrev);
        prev = theta;
        gPrev = g;
        theta = next;
    }
    if (std::abs(x(theta) - target) < 1e-6)
        return theta;
    // Neither converged (v19: one face in 200 of seed 1, whose own shape fields tilt the nose's
    // flank, was left 7.4 mm short of al): bisect between the midline, where x is 0, and the
    // first azimuth out from it that reaches the target.
    double lo = 0, hi = 0;
    for (double t = 0.02; t < 1.5; t += 0.02)
        if (x(t) >= target) {
            hi = t;
            break;
        }
    if (hi == 0)
        return theta; // the skin never reaches the target; makeFrame's callers see the miss
    for (int i = 0; i < 60; ++i) {
        const double mid = (lo + hi) / 2;
        (x(mid) < target ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
}

// The elevation at which the base midline reaches height y, between lo and hi.
double solvePhiBase(const Frame& f, double y, double lo, double hi)
{
    for (int i = 0; i < 60; ++i) {
        const double mid = (lo + hi) / 2;
        (f.depth(mid) * std::tan(mid) < y ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
}

void placeEyes(Frame& f)
{
    for (int s = 0; s < 2; ++s) {
        const double sign = s == 1 ? 1 : -1;
        Ellipsoid& e = f.eye[s];
        // Seen from the front the eye must fill the whole fissure (globe plus the conjunctiva
        // and caruncle at the corners), so its x semi-axis spans en..ex with a margin.
        const double xc = (f.p.enen + f.p.exex) / 4;
        e.right = Eigen::Vector3d(1, 0, 0);
        e.up = Eigen::Vector3d(0, 1, 0);
        e.forward = Eigen::Vector3d(0, 0, 1);
        e.a = (f.p.exex - f.p.enen) / 4 + 3.0;
        e.b = e.c = 12.0;
        const double thetaC = std::atan2(xc, f.zf - 10);
        const double rho = rhoBase(f, thetaC, 0);
        const double zEnvelope = std::sqrt(std::max(sq(rho) - sq(xc), 1.0));
        e.centre = Eigen::Vector3d(sign * xc, 0.5 * f.p.canthalTilt, zEnvelope - f.p.eyeSet - e.c);
    }
    f.xEye = (f.p.enen + f.p.exex) / 4;
}

} // namespace

// How much lower than half the brow's height above the canthal line n sits (v21), which moves
// the nose, mouth and chin down from the eyes by as much (n-sn, n-gn and sn-sto are Farkas norms
// and stay). Until v20 n sat at half the brow's height, 13.6 mm above the mean face's eye corners,
// and the eye corners 38.8 mm above sn and 57.4 mm above the mouth's: the mid-face 16% short for
// the eyes' width. ICT-FaceKit's mean face has 45.4 and 68.5 mm there (ex-ex 89.5 in both), and
// the mean of the 68 landmarks of real photographs used for face alignment puts the mouth's
// corners 0.78 ex-ex below the eyes' (ours 0.64). With 6 mm (and v21's refitted means) the
// mean face has its eyes 45.2 mm above sn and n 7.1 mm above them, between the lash line and the
// lid's crease as on real faces (docs/realism.md, "Now (6 December, v21)").
constexpr double kNasionLowering = 6.0;

Frame makeFrame(const FaceParams& p)
{
    Frame f;
    f.p = p;
    f.zf = p.faceDepth;
    // The glabella, the forehead above it and the rows of both stay where they were with n at
    // half the brow's height (until v21): they belong to the brow, which stays put over the eyes.
    const double yHalfBrow = 0.5 * p.browHeight;
    f.yN = yHalfBrow - kNasionLowering;
    // sn stands on the subnasal ridge (face_frame.h), as far in front of where v19 put it as the
    // ridge is high there; the profile's knot at sn stays where v19 put it (below).
    const double zSnBase = f.zf + 1.0;
    f.zSn = zSnBase + subnasalRidge(0, 0);
    f.ySn = f.yN - std::sqrt(sq(p.nsn) - sq(f.zSn - f.zf));
    f.yPrn = f.ySn + p.tipRise;
    f.zPrn = f.zSn + p.tipProtrusion;
    f.zSto = f.zf - 0.5 + 0.5 * p.lipProtrusion;
    // sn-sto is Farkas' upper lip height, a straight distance: sn now stands well in front of sto.
    f.ySto = f.ySn - std::sqrt(sq(p.snsto) - sq(f.zSn - f.zSto));
    f.zGn = f.zf + p.chinProjection - 14;
    f.yGn = f.yN - std::sqrt(sq(p.ngn) - sq(f.zf - f.zGn));
    f.yPg = f.yGn + std::min(11.0, 0.35 * (f.ySto - f.yGn));
    f.zPg = f.zf + p.chinProjection - 1;
    f.fold = nasolabialCurve(f);
    const double slope = p.foreheadSlope;

    f.yG = yHalfBrow + 11;
    // Midline profile without nose, lips and chin boss: (y, z) pairs top to bottom.
    const std::vector<std::pair<double, double>> profile = {
        // The forehead knots were moved forward (by 16, 11 and 5 mm) towards the ICT-FaceKit
        // mean face (issue 16, docs/realism.md "Calibration").
        { f.yG + 89, f.zf - 33 - 0.6 * slope },
        { f.yG + 61, f.zf - 10 - 0.4 * slope },
        { f.yG + 34, f.zf - 0.5 - 0.2 * slope },
        { f.yG + 11, f.zf - 0.5 + 0.3 * p.nasionDepth },
        { f.yG, f.zf + p.nasionDepth },
        { f.yN, f.zf },
        { lerp(f.yN, f.ySn, 0.5), f.zf - 1.5 },
        // At v19's depth: the knot's elevation, atan2(y, z), then stays too. With the knot at sn's
        // target in front of it, the profile's elevations moved 1.2 degrees (2 mm) and with them
        // every lip row (ls 2.4 mm up).
        { f.ySn, zSnBase },
        { f.ySto, f.zSto },
        { f.yPg, f.zPg - p.chinHeight },
        { f.yGn, f.zGn },
        { f.yGn - 7, f.zGn - 20 },
        { f.yGn - 13, f.zGn - 40 },
        { f.yGn - 40, f.zGn - 50 },
    };
    for (auto it = profile.rbegin(); it != profile.rend(); ++it) {
        f.depth.x.push_back(std::atan2(it->first, it->second));
        f.depth.y.push_back(it->second);
    }
    f.depth.build();

    // Half width at the side of the head, by elevation (radians).
    const double hb = p.headBreadth / 2, zy = p.cheekboneWidth / 2, go = p.jawWidth / 2, neck = p.neckWidth / 2;
    const std::vector<std::pair<double, double>> widths = {
        { -1.45, std::min(0.85 * go, 0.8 * neck) },
        { -1.1, std::min(0.9 * go, 0.86 * neck) },
        { -0.85, go },
        { -0.5, 0.5 * (go + zy) },
        { -0.2, std::max(zy, 0.94 * hb) },
        { 0.1, hb },
        { 0.45, 0.97 * hb },
        { 0.8, 0.8 * hb },
        { 1.2, 0.55 * hb },
    };
    for (const auto& [phi, w] : widths) {
        f.width.x.push_back(phi);
        f.width.y.push_back(w);
    }
    f.width.build();

    f.phiN = std::atan2(f.yN, f.zf);
    f.phiSn = std::atan2(f.ySn, f.zSn);
    f.phiSto = std::atan2(f.ySto, f.zSto);
    f.phiPg = std::atan2(f.yPg, f.zPg);
    f.phiGn = std::atan2(f.yGn, f.zGn);
    f.phiPrn = std::atan2(f.yPrn, f.zPrn);
    // Vermilion borders at their sampled heights, but never closer than 40% of the way to
    // the nose or the chin, so short faces keep every grid row distinct.
    f.phiLs = solvePhiBase(f, std::min(f.ySto + p.upperVermilion, lerp(f.ySto, f.ySn, 0.6)), f.phiSto, f.phiSn);
    f.phiLi = solvePhiBase(f, std::max(f.ySto - p.lowerVermilion, lerp(f.ySto, f.yPg, 0.6)), f.phiPg, f.phiSto);
    f.phiBrow = solvePhiBase(f, p.browHeight + 0.5 * yHalfBrow, f.phiN, 1.2);
    f.phiTopFront = solvePhiBase(f, yHalfBrow + 62, f.phiBrow, 1.3);
    f.phiBottomFront = std::atan2(f.yGn - 8, f.zGn - 26);
    f.rEye = f.zf - 8;
    f.rMouth = f.zSto;
    f.mouthScale = f.depth(f.phiSto) / sq(std::cos(f.phiSto));

    // Nose height at prn so that the tip lands on its target.
    f.noseTip = 0;
    f.xAl = p.alal / 2;
    f.thetaEn = p.enen / 2 / f.rEye;
    f.thetaEx = p.exex / 2 / (f.rEye - 15);
    placeEyes(f);
    const double prnDistance = std::hypot(f.yPrn, f.zPrn);
    f.noseTip = prnDistance - neutralRadius(f, 0, f.phiPrn);

    // The features add a little radius on the midline (glabella, chin boss, detail), so move
    // the profile's knots at n, sn, pg and gn until the finished skin passes through their
    // targets exactly; the nose height follows.
    const std::pair<double, double> exact[] = { { f.yN, f.zf }, { f.ySn, f.zSn }, { f.yPg, f.zPg }, { f.yGn, f.zGn } };
    // Sixteen passes: the shape fields and the face-wide factors (face_params.h) tilt the
    // midline; three left 0.4 mm, six 0.13 mm once the factors came (v15), ten 0.016 mm, and
    // with v21's nose, mouth and chin lower under the eyes ten left 0.19 mm, sixteen 0.027.
    for (int pass = 0; pass < 16; ++pass) {
        for (const auto& [y, z] : exact) {
            const double phi = std::atan2(y, z);
            const size_t k = static_cast<size_t>(std::min_element(f.depth.x.begin(), f.depth.x.end(), [&](double a, double b) {
                return std::abs(a - phi) < std::abs(b - phi);
            }) - f.depth.x.begin());
            f.depth.y[k] += (std::hypot(y, z) - neutralRadius(f, 0, phi)) * std::cos(phi);
        }
        f.depth.build();
        f.noseTip = prnDistance - (neutralRadius(f, 0, f.phiPrn) - f.noseTip);
    }

    // Columns: solve the azimuths that put en, ex, al and ch at their sampled widths; the
    // eyeballs depend on en and ex, so settle both three times (twice left 5e-4 mm with the
    // shape fields).
    for (int pass = 0; pass < 3; ++pass) {
        f.thetaEn = solveTheta(f, p.enen / 2, 0, f.thetaEn);
        f.thetaEx = solveTheta(f, p.exex / 2, p.canthalTilt / f.rEye, f.thetaEx);
        placeEyes(f);
    }
    // al's column starts where the ala's sideways swell (alaSpread) will carry it out to al-al:
    // secant steps on its neutral X (the swell falls by about 0.4 mm per mm outwards there).
    f.thetaAl = p.alal / 2 / f.zf;
    auto alMiss = [&](double x) {
        f.thetaAl = solveTheta(f, x, f.phiPrn, f.thetaAl);
        return x + alaSpread(f, f.thetaAl, f.phiPrn).x() - p.alal / 2;
    };
    double x0 = p.alal / 2, m0 = alMiss(x0), x1 = x0 - m0, m1 = alMiss(x1);
    for (int pass = 0; pass < 6 && std::abs(m1) > 1e-9 && m1 != m0; ++pass) {
        const double x2 = x1 - m1 * (x1 - x0) / (m1 - m0);
        x0 = x1;
        m0 = m1;
        x1 = x2;
        m1 = alMiss(x1);
    }
    f.xAl = x1;
    f.thetaCh = solveTheta(f, p.chch / 2, f.phiSto, p.chch / 2 / f.zf);
    return f;
}

} // namespace facesketch::dataset::detail

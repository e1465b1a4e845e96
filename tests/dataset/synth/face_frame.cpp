// The per-face frame of the synthetic generator: the monotone profile spline, the smooth
// helpers, the base head shape, and makeFrame's promise that the finished skin passes through
// the sampled landmark targets.
#include "dataset/synth/face_frame.h"
#include "core/error.h"
#include "test_common.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

using namespace facesketch;
using namespace facesketch::dataset;
using namespace facesketch::dataset::detail;

TEST_CASE("face_frame: Monotone passes through its knots, never overshoots and extends linearly")
{
    // A step-like series: an unconstrained cubic spline overshoots both corners.
    Monotone spline;
    spline.x = { 0, 1, 2, 3, 4, 5 };
    spline.y = { 0, 0, 0.1, 5, 5, 5.2 };
    spline.build();
    for (size_t i = 0; i < spline.x.size(); ++i)
        REQUIRE(spline(spline.x[i]) == Approx(spline.y[i]).margin(1e-12));
    double previous = spline(0);
    for (int k = 1; k <= 500; ++k) {
        const double t = 5.0 * k / 500, value = spline(t);
        REQUIRE(value >= previous - 1e-12);
        const size_t i = std::min<size_t>(static_cast<size_t>(t), 4);
        REQUIRE(value >= std::min(spline.y[i], spline.y[i + 1]) - 1e-12);
        REQUIRE(value <= std::max(spline.y[i], spline.y[i + 1]) + 1e-12);
        previous = value;
    }
    // Outside the knots: the end slopes, continued as straight lines.
    REQUIRE(spline(-2) == Approx(spline.y.front() + spline.m.front() * -2));
    REQUIRE(spline(7) == Approx(spline.y.back() + spline.m.back() * 2));
    // Flat runs stay flat.
    REQUIRE(spline(0.5) == 0);
    REQUIRE(spline(3.5) == 5);
}

TEST_CASE("face_frame: Monotone rejects knots that do not increase, naming the index")
{
    Monotone spline;
    spline.x = { 0, 1, 1, 2 };
    spline.y = { 0, 1, 2, 3 };
    REQUIRE_THROWS_WITH(spline.build(), Catch::Contains("not increasing at 1"));
}

TEST_CASE("face_frame: smax is max apart from a blend of width k, and the smooth steps stay in [0, 1]")
{
    REQUIRE(smax(3, 1, 0.5) == 3);
    REQUIRE(smax(-1, 4, 2) == 4);
    // Within k of each other the blend lies above both, by k / 4 when they are equal.
    REQUIRE(smax(2, 2, 1) == Approx(2.25));
    REQUIRE(smax(2, 1.8, 1) > 2);
    // Continuous where the blend ends.
    REQUIRE(smax(2, 1.0 + 1e-9, 1) == Approx(smax(2, 1.0 - 1e-9, 1)).margin(1e-8));
    REQUIRE(smoothstep(0, 1, -3) == 0);
    REQUIRE(smoothstep(0, 1, 4) == 1);
    REQUIRE(smoothstep(0, 1, 0.5) == 0.5);
    REQUIRE(smoothstep(2, 0, 0.5) == Approx(fall(0.25)));
    REQUIRE(fall(0) == 1);
    REQUIRE(fall(1) == 0);
}

TEST_CASE("face_frame: direction follows the world convention")
{
    const double half = std::numbers::pi / 2;
    REQUIRE((direction(0, 0) - Eigen::Vector3d(0, 0, 1)).norm() < 1e-15);      // the face looks down +z
    REQUIRE((direction(half, 0) - Eigen::Vector3d(1, 0, 0)).norm() < 1e-15);   // positive azimuth: the face's left
    REQUIRE((direction(0.3, half) - Eigen::Vector3d(0, 1, 0)).norm() < 1e-15); // positive elevation: up
    for (const double theta : { -2.0, -0.4, 0.7, 3.0 })
        for (const double phi : { -1.2, 0.0, 0.9 })
            REQUIRE(direction(theta, phi).norm() == Approx(1));
}

TEST_CASE("face_frame: makeFrame puts the profile landmarks and the eye and mouth corners on their targets")
{
    // Largest miss (mm) over 200 identities of: the midline targets n, sn, pg, gn, prn; the
    // half widths of en, ex, al, ch along the neutral skin at their solved azimuths.
    double profileMiss = 0, eyeMiss = 0, noseMiss = 0, mouthMiss = 0;
    for (int index = 0; index < 200; ++index) {
        const FaceParams p = sampleFaceParams(1, index);
        const Frame f = makeFrame(p);
        INFO("identity " << index);
        // The base head: depth on the midline, the side width at 90 degrees.
        for (const double phi : { -0.9, -0.3, 0.2, 0.7 }) {
            REQUIRE(rhoBase(f, 0, phi) == Approx(f.depth(phi)));
            REQUIRE(rhoBase(f, std::numbers::pi / 2, phi) == Approx(f.width(phi)));
        }
        // Stomion is a knot of the profile, so the midline reaches its height exactly.
        REQUIRE(midY(f, f.phiSto) == Approx(f.ySto).margin(1e-9));
        const std::pair<double, double> targets[]
            = { { f.yN, f.zf }, { f.ySn, f.zSn }, { f.yPg, f.zPg }, { f.yGn, f.zGn }, { f.yPrn, f.zPrn } };
        for (const auto& [y, z] : targets)
            profileMiss = std::max(profileMiss, std::abs(neutralRadius(f, 0, std::atan2(y, z)) - std::hypot(y, z)));
        auto x = [&](double theta, double phi) { return neutralRadius(f, theta, phi) * std::cos(phi) * std::sin(theta); };
        eyeMiss
            = std::max({ eyeMiss, std::abs(x(f.thetaEn, 0) - p.enen / 2), std::abs(x(f.thetaEx, p.canthalTilt / f.rEye) - p.exex / 2) });
        // al's skin moves out with the ala's sideways swell after the chart is solved (v23).
        noseMiss = std::max(noseMiss, std::abs(x(f.thetaAl, f.phiPrn) + alaSpread(f, f.thetaAl, f.phiPrn).x() - p.alal / 2));
        mouthMiss = std::max(mouthMiss, std::abs(x(f.thetaCh, f.phiSto) - p.chch / 2));
        // The landmark rows keep their order from top to bottom.
        REQUIRE(f.phiTopFront > f.phiBrow);
        REQUIRE(f.phiBrow > f.phiN);
        REQUIRE(f.phiN > f.phiPrn);
        REQUIRE(f.phiPrn > f.phiSn);
        REQUIRE(f.phiSn > f.phiLs);
        REQUIRE(f.phiLs > f.phiSto);
        REQUIRE(f.phiSto > f.phiLi);
        REQUIRE(f.phiLi > f.phiPg);
        REQUIRE(f.phiPg > f.phiGn);
        REQUIRE(f.phiGn > f.phiBottomFront);
        // Eyeballs: mirror images behind the fissure, wide enough to fill it from en to ex.
        REQUIRE(f.eye[0].centre.x() == -f.eye[1].centre.x());
        REQUIRE(f.eye[0].centre.y() == f.eye[1].centre.y());
        REQUIRE(f.eye[1].centre.x() - f.eye[1].a < p.enen / 2);
        REQUIRE(f.eye[1].centre.x() + f.eye[1].a > p.exex / 2);
    }
    std::cout << "face_frame: largest miss over 200 identities: profile " << profileMiss << " mm, en/ex " << eyeMiss << " mm, al "
              << noseMiss << " mm, ch " << mouthMiss << " mm\n";
    // Measured at 0.027, 1e-13, 8e-10 and 0.08 mm (v21; v15: 0.016, 1e-13, 0.0097 and 0.32): the
    // profile knots get sixteen correction passes;
    // the corners' azimuths are 8 fixed-point steps and then secant steps (without those the
    // lower nose's steep flank left al 0.07 mm short), and the lips' steep radius near ch leaves
    // ch furthest from converged (0.5 mm is 1% of ch-ch).
    REQUIRE(profileMiss < 0.1);
    REQUIRE(eyeMiss < 1e-4);
    REQUIRE(noseMiss < 0.01);
    REQUIRE(mouthMiss < 0.5);
}

// The alae's sideways swell (v23, face_shape.cpp alaSpread): a displacement along x only, mirror
// symmetric, outwards from the midline, nothing on the midline or away from the nose, at most
// the 3 mm it is built to reach, and al itself carried outwards (its column starts inside al-al,
// Frame::xAl).
TEST_CASE("face_frame: the alae swell sideways, mirror symmetric, outwards and only round the alae")
{
    for (int index = 0; index < 20; ++index) {
        const FaceParams p = sampleFaceParams(2, index);
        const Frame f = makeFrame(p);
        INFO("identity " << index);
        double largest = 0;
        for (double theta = 0; theta <= 0.6; theta += 0.01)
            for (double phi = f.phiSn - 0.1; phi <= f.phiN; phi += 0.01) {
                const Eigen::Vector3d right = alaSpread(f, theta, phi), left = alaSpread(f, -theta, phi);
                REQUIRE(right.y() == 0);
                REQUIRE(right.z() == 0);
                REQUIRE(right.x() >= 0);
                REQUIRE(left.x() == Approx(-right.x()).margin(1e-12));
                largest = std::max(largest, right.x());
            }
        REQUIRE(largest > 2.5);
        REQUIRE(largest <= 3.0);
        REQUIRE(alaSpread(f, 0, f.phiPrn).norm() == 0);         // the midline stays whole
        REQUIRE(alaSpread(f, f.thetaEx, 0).norm() == 0);        // the eye's corner
        REQUIRE(alaSpread(f, f.thetaCh, f.phiSto).norm() == 0); // the mouth's corner
        const double atAl = alaSpread(f, f.thetaAl, f.phiPrn).x();
        REQUIRE(atAl > 0);
        REQUIRE(f.xAl == Approx(p.alal / 2 - atAl).margin(0.01));
    }
}

// Vertices of the synthetic face (face_generator.h) from its frame (face_frame.h): the star-shaped
// skin r(theta, phi) as base + bone (nose, brows, sockets, cheekbones, chin) + soft tissue
// (lips, philtrum, cheeks, eyebrows, detail) and the nose's tip dome, the nostrils' vestibules
// pushed into the nose, the alae spread sideways, eyelids resting on the eyeballs, the pose
// deformers that slide skin over that structure and turn the jaw, and the eyeball, teeth and
// tongue meshes.
//
// Sources: proportions from Farkas LG, Anthropometry of the Head and Face, 2nd ed., 1994
// (face_params.cpp); the landmark set of thesis Table 3.1; the 36 poses of thesis 5.2.
#include "dataset/synth/face_generator.h"

#include "core/error.h"
#include "dataset/synth/face_frame.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace facesketch::dataset {

using namespace detail;

namespace {

constexpr double kSide = 100.0 * M_PI / 180.0; // the grid reaches 10 degrees behind the ears
constexpr double kSupratip = 1.0;              // mm, the supratip break's depth (bone(): nose)
// The skin lip above and below the vermilion (soft(), lipProfile()): it fades from kShelfFade of
// the way to each corner (v13), and it comes to rest at the nose's base, but at least
// kUpperSpanMin and at most kUpperSpanMax mm past the upper border, and kLowerSpan mm past the
// lower one, about where the mentolabial sulcus lies (bone()) (v16).
constexpr double kShelfFade = 0.4;
// Below gn the population's mean fields fade out (soft(), v18): from kUnderChinFrom rad (about
// 8 mm) below gn, over kUnderChinOver rad.
constexpr double kUnderChinFrom = 0.06, kUnderChinOver = 0.1;
constexpr double kUpperSpanMin = 5.0, kUpperSpanMax = 14.0, kLowerSpan = 9.0; // mm
// The brow ridge's crest falls kBrowArch mm 20 mm to either side of the eye's centre, so the
// ridge follows the orbit's upper rim; and the temple lies back by up to kTemporalHollow mm
// behind the orbit's lateral rim (bone(), v14). Until v13 the ridge was a horizontal band across
// the face and the mean shape field dug a 4 mm trough at eye level out to the temples in place of
// the hollow, which drew a horizontal band on the curvature maps from temple to temple. With both,
// and the mean field refitted, the mean face is 0.02 mm nearer ICT's (docs/realism.md, "v14").
constexpr double kBrowArch = 8.0;       // mm
constexpr double kTemporalHollow = 4.0; // mm

// The lower nose (issue 16, docs/realism.md "nostril vestibules"): from prn down, blending into the
// dorsum over the first kLobuleBlend of the way up to n, the nose's cross-section is wider and
// fuller than the dorsum's: 0.88 (1 - |x|^a)^b with x the offset over kLobuleSpread tip widths
// (1.6 on the dorsum), a = kLobuleSquare (2 on the dorsum) and b = kLobuleFullness (1.3 on the
// dorsum), so it has room for the nostrils' vestibules.
constexpr double kLobuleSpread = 2.2;
constexpr double kLobuleSquare = 2.4;
constexpr double kLobuleFullness = 0.7;
constexpr double kLobuleBlend = 0.4;
// The nostril's radial dimple: kNostrilDimple tip heights deep, kNostrilDimpleX nostril sizes
// wide and kNostrilDimplePhi of sn..prn tall (half-axes). At 0.8 and 0.25 (v6) a 9 mm pit over 3 mm
// had walls so steep that the quad between two rows of the high grid folded (normals more than
// 150 degrees apart) on 18 of 250 faces (seed 1); at 1.2 and 0.45 (v7) none did. Since v9 the
// vestibule below makes the opening and the dimple deepens its floor, 0.3 deep (0.45 until v8).
constexpr double kNostrilDimple = 0.3;
constexpr double kNostrilDimpleX = 1.2;
constexpr double kNostrilDimplePhi = 0.45;

// Nostril vestibules: the skin inside each nostril's opening (the footprint, an ellipse in the
// neutral chart centred kNostrilOut of the way out to al and kNostrilAt of the way from sn to prn,
// with half-axes kNostrilHalfWidth nostril sizes and kNostrilHalfHeight of sn..prn, face_frame.h)
// is moved up into the nose and back, along (0, 1, -kVestibuleBack), by up to kVestibuleDepth mm,
// smoothly from the footprint's rim, and never closer than kVestibuleWall mm to the far side of
// the neutral skin.
// The columella between the two footprints keeps its skin: within kColumellaHalf mm of the midline
// nothing moves, and the depth reaches its full value at kColumellaHalf + kColumellaBlend.
//
// v9 (docs/realism.md, "Now (3 December, late)"): until v8 the footprints were 1.55 nostril sizes
// wide and 0.45 of sn..prn tall, and the two of them together hollowed the whole underside of the
// lobule, columella included, into one cavity that read from the front as a dark band and from
// below as one hole. Now each is 1.2 by 0.35, further out (0.4 of the way to al, 0.30-0.37 before),
// deeper (14 mm, 12-13 before) and the columella is kept; the high grid has 8 rows from prn to sn
// (5 before, face_topology.cpp) to hold two openings with a columella between them. v23: 13 mm
// (below, kColumellaBlend).
constexpr double kVestibuleDepth = 13.0; // mm
// Back 1.4 since v12 (1.6 in v11, 2.4 in v9-v10, 2.2 in v8, 2.5 before). Pointing further up, the
// pocket's walls stand more nearly parallel to the rays of a front or a below view, so without
// any ambient occlusion in the renderer the opening reads dark from below and from the front, as
// ICT's do, and the mean face comes nearer ICT's (nose 2.01 mm at 2.4, 1.81 at 1.4; docs/realism.md
// "v11 and v12"). Until v12 the labelled nostril rings lay inside the footprints and rode up
// into the pockets with them (up to 12.1 mm above sn at 1.2, over the face_shape test's 12); now
// they lie on the rim (face_topology.cpp). What bounds it now: at 1.2 the pocket's front wall folds
// (one face in 250 on seeds 5 and 7), at 1.3 and above none does (seeds 1, 3, 5, 7). That wall,
// seen from inside the nose, faces the head's centre on nearly every face (the tests exempt the
// nose's underside for this).
constexpr double kVestibuleBack = 1.4;
constexpr double kVestibuleWall = 1.0; // mm
// The pocket is kVestibuleDepth deep over the inner kVestibuleFloor of the footprint's radius and
// rises to the rim over the rest. Until v19 it rose over all of it (0), a funnel whose rim no
// render showed: from below the nostrils were dark smudges. At 0.3 (v20) the opening has a wall
// under its rim, reads as an oval from below, and holds more of the room ICT-FaceKit's nostrils
// have (the nose's mean-face distance to ICT's 0.1 mm RMS nearer; no fold on seeds 1, 3, 5 and
// 7, 250 high faces each). At 0.45 the rim was ragged on the high grid, whose rows lie about
// 2.5 mm apart there.
constexpr double kVestibuleFloor = 0.3;
// v23: the blend 3 mm (2 until v22) and the pockets 13 mm deep (14 until v22). On the low grid the
// columella is one column of vertices with a pocket vertex on either side, and the two triangles
// between them and the columella's front edge stand nearly back to back. With the tip dome and the
// alae's changes (below) they folded (normals more than 150 degrees apart) on 4 of 250 faces of
// seed 1 and 2 of seed 3; with the blend at 3 mm on 2 and 0, and on 1 of seed 11 (the pose tests'
// face 5); with both on none of the three seeds (v22: 2, 0 and 0). The nose's mean-face distance
// pays 0.05 mm RMS for the millimetre of depth; a 4 mm blend folded a high face instead.
constexpr double kColumellaHalf = 1.5;  // mm
constexpr double kColumellaBlend = 3.0; // mm

// The alar lobule: an elliptic bump on each side of the lower nose, its centre kAlaIn alar radii
// inside al and kAlaAt of the way from sn up to prn, its half-height kAlaAbove alar radii above the
// centre and kAlaBelow below, kAlaHeight times (0.34 tip heights + 2 mm) high, rounded as
// (1 - d)^kAlaRound. Until v7 it sat at 0.55 with 0.85 both ways, full height, and on the
// downward-facing underside the radial bump grew down and forward into a tab that hung 2 mm below
// sn in front of the nostril, so from the front each nostril showed as a dark notch between the
// columella and a tab. v8 and v9 lifted it (0.8 / 0.4, then 0.9 / 0.3); v10 made it 0.6 below and
// 0.6 of the height. Until v19 its centre lay a whole radius inside al, where the lobule's body
// (bone(): the lower nose's wide cross-section) stood higher than it, so the smooth maximum of the
// two left no ala to see: a section 16 mm from the midline, where ICT-FaceKit's mean face has a
// bulge 11 mm proud of the alar base, was flat. v20 (docs/realism.md, "v20"): the centre moves out
// to 0.7 radii inside al and up, beyond prn's height, because a radial bump on the underside,
// 45 mm below the head's centre, grows forward and down; taller (1.1 / 1.3 radii), higher and
// rounder, 16 mm out it peaks 10 mm above sn as ICT's bulge does, 1.6 mm behind it.
// v23 (docs/realism.md, "v23"): 0.7 of the height (1.15 until v22) and rounded as (1 - d)^2
// (^0.8 until v22, a rim standing vertically out of the skin). Near al a radial bump grows
// forwards, not sideways, so the full-height lobule stood out towards a viewer in front as a
// hanging knob with a dark crescent inside it; the ala's sideways swell is now alaSpread's.
constexpr double kAlaIn = 0.7;
constexpr double kAlaAt = 1.35;
constexpr double kAlaAbove = 1.1;
constexpr double kAlaBelow = 1.3;
constexpr double kAlaHeight = 0.7;
constexpr double kAlaRound = 2.0;
// The ala's sideways swell (v23, alaSpread()): the skin within kAlaSpreadRadius alar radii of
// the lobule's centre (neutral chart) moves out from the midline by up to kAlaSpread mm, as
// kAlaSpread (1 - d^2)^2 with d the distance over that radius. A displacement, like the
// vestibules, since a radial height cannot push the skin sideways there. With it the lower nose
// reads from the front as a bell whose alae flare beside the lobule, as real noses do, and the
// mean face comes nearer ICT-FaceKit's (trial without the tip dome below: nose 1.54 -> 1.50 mm
// RMS, bending difference 43.4 -> 39.3 1/m). makeFrame solves al's column so that al lands on
// its target after the swell (Frame::xAl).
constexpr double kAlaSpread = 3.0;       // mm
constexpr double kAlaSpreadRadius = 1.5; // alar radii
// The tip dome (v23, tipDome()): an ellipsoid kTipDomeHalfWidth tip widths wide, kTipDomeHalfHeight
// of prn's height above sn tall and kTipDomeDepth mm deep (half-axes), its front at the nose's prn
// (so the frame's solve for the nose's height still puts prn on its target), joined to the skin by
// a smooth maximum kTipDomeBlend mm wide. The radial lower nose (bone()) meets its underside at prn
// in a corner of a few mm radius that read in profile as a wedge; the dome rounds it as
// ICT-FaceKit's tips are round. Outside the dome's silhouette (seen from the head's centre) the
// ray's distance falls kTipDomeFall half-heights per unit of the miss. Seen from the side, the
// nose's outline 2 mm below prn now lies 1.5 mm behind it, 2.6 without the dome and 3.5 in v22 (the
// face_shape test; ICT-FaceKit's faces 0.5). Centred higher, by 0.3 half-heights, the dome left the
// tip as sharp as without it. docs/realism.md, "v23".
constexpr double kTipDomeHalfWidth = 1.4;
constexpr double kTipDomeHalfHeight = 0.6;
constexpr double kTipDomeDepth = 10.0; // mm
constexpr double kTipDomeBlend = 5.0;  // mm
constexpr double kTipDomeFall = 3.0;
// A nose wrinkle (disgust, anger) lifts each alar lobule by kAlaWrinkleLift mm per unit of
// FaceActions::noseWrinkle, and its skin rides up with it (warp()): the lobule's own skin, out
// to kAlaSlideFrom alar radii from its centre, moves the whole way and the skin round it less,
// to nothing at kAlaSlideTo radii. Until v21 only the radial bump rose (bone()) and the skin
// stayed, so the bump's steep upper flank passed under fixed vertices, and on the ultra grid
// triangles at prn's height turned over in `disgust` (faces 5 and 14 of the pose tests' seed;
// with the lift halved, face 5 still turned two over).
constexpr double kAlaWrinkleLift = 0.6;
constexpr double kAlaSlideFrom = 1.0, kAlaSlideTo = 2.0;
// The lower nose's midline rises from sn to prn as 1 - u^kColumellaCurve (u: 1 at sn, 0 at prn).
// At 1.8 (until v19) the columella left sn nearly level, rising 10 degrees, a nasolabial angle
// near 90 degrees; at 1.2, with the subnasal ridge (face_frame.h) under it, the mean face's
// rises about 22 degrees, ICT-FaceKit's about 20.
constexpr double kColumellaCurve = 1.2;
// Where the nasolabial fold starts (nasolabialCurve): 2 mm above kFoldAt of the way from sn up to
// prn, the alar lobule's centre until v19. v20 moved that centre up (kAlaAt) but not the lobe
// one sees, which a radial bump on the underside draws lower; the fold stays.
constexpr double kFoldAt = 0.9;

// The alar lobule's radius and its centre (|X|, Y in mm) on face `f` under a nose wrinkle of
// `wrinkle` (FaceActions::noseWrinkle; 0 for the neutral face): bone() raises the lobule there,
// warp() moves its skin with it.
struct AlarLobule {
    double radius, x, y;
};
AlarLobule alarLobule(const Frame& f, double wrinkle)
{
    const double radius = f.p.alaSize * (1 + 0.04 * wrinkle);
    return { radius, f.p.alal / 2 - kAlaIn * radius, lerp(f.ySn, f.yPrn, kAlaAt) + kAlaWrinkleLift * wrinkle };
}

// Radial height of nose, brows, sockets, cheekbones and chin: the parts that do not slide.
double bone(const Frame& f, double theta, double phi, double X, double Y, const FaceActions& act)
{
    const FaceParams& p = f.p;
    const double ax = std::abs(X);
    double r = 0;

    // Nose: a midline height profile over phi (columella, rounded lobule, dorsum with hump),
    // a flat-topped, steep-sided cross-section, alar lobules and nostril pits.
    double body = 0;
    if (phi > f.phiSn && phi < f.phiN) {
        double height, halfWidth;
        if (phi <= f.phiPrn) {
            const double u = 1 - (phi - f.phiSn) / (f.phiPrn - f.phiSn);
            height = f.noseTip * (1 - std::pow(u, kColumellaCurve));
            halfWidth = p.tipWidth;
        } else {
            const double t = (phi - f.phiPrn) / (f.phiN - f.phiPrn);
            height = f.noseTip * sq(1 - t) * (1 + 2 * t) + p.dorsumHump * sq(std::sin(M_PI * t)) * smoothstep(0, 0.3, t);
            // Supratip break: the dorsum dips just above the lobule, as on real noses, so the
            // tip is a dome with prn at its front. Without it the profile is flat to first order
            // at prn (the cubic's slope is 0 there), and a small slope from the shape fields
            // moved the most forward vertex 4 mm up the dorsum, 0.007 mm further forward (issue
            // 16, docs/realism.md). It costs 0.01 mm of the mean-face distance to ICT.
            const double s = t * (f.yN - f.yPrn);
            height -= kSupratip * (1 - std::exp(-sq(s / 4))) * std::exp(-sq((s - 12) / 9));
            halfWidth = lerp(p.tipWidth, p.bridgeWidth, smoothstep(0, 0.55, t)) + 2.5 * smoothstep(0.6, 1, t);
        }
        const double lower = phi <= f.phiPrn ? 1.0 : 1 - smoothstep(0, kLobuleBlend, (phi - f.phiPrn) / (f.phiN - f.phiPrn));
        const double x = ax / (halfWidth * lerp(1.6, kLobuleSpread, lower));
        const double cross
            = x < 1 ? 0.88 * std::pow(1 - std::pow(x, lerp(2.0, kLobuleSquare, lower)), lerp(1.3, kLobuleFullness, lower)) : 0;
        body = height * (cross + 0.12 * std::exp(-sq(X / (2.4 * halfWidth))));
    }
    const auto [ra, alaX, alaY] = alarLobule(f, act.noseWrinkle);
    const double da = sq((ax - alaX) / ra) + sq((Y - alaY) / ((Y < alaY ? kAlaBelow : kAlaAbove) * ra));
    const double ala = da < 1 ? kAlaHeight * (0.34 * f.noseTip + 2.0) * std::pow(1 - da, kAlaRound) : 0;
    r += smax(body, ala, 6.0);
    const double phiNostril = lerp(f.phiSn, f.phiPrn, kNostrilAt);
    const double dn
        = sq((ax - 0.45 * f.xAl) / (kNostrilDimpleX * p.nostrilSize)) + sq((phi - phiNostril) / (kNostrilDimplePhi * (f.phiPrn - f.phiSn)));
    if (dn < 1)
        r -= kNostrilDimple * f.noseTip * sq(1 - dn);

    // Brow ridge over each orbit, arched along the orbit's upper rim (kBrowArch), and the glabella
    // between them.
    const double browLateral = smoothstep(4, 14, ax) * (1 - smoothstep(p.exex / 2, p.exex / 2 + 18, ax));
    const double browCrest = p.browHeight - 5 - kBrowArch * sq((ax - f.xEye) / 20);
    r += p.browRidge * std::exp(-sq((Y - browCrest) / 8)) * browLateral;
    r += 0.35 * p.browRidge * std::exp(-sq(X / 9) - sq((Y - f.yG) / 8));
    // Orbital socket: the face sinks around the eyeball so the lids drape over it.
    const double ds = sq((ax - f.xEye) / 21) + sq((Y - 1) / 15);
    if (ds < 1)
        r -= 8 * sq(1 - ds);
    r += p.cheekboneHeight * std::exp(-sq((ax - 0.36 * p.cheekboneWidth) / 16) - sq((Y + 20) / 14));
    // Paranasal hollow: the maxilla beside the nose and under the orbit lies behind the
    // envelope of the base surface (issue 16: its amplitude, place and size were set by the
    // mean-face distance to the ICT-FaceKit mean face, docs/realism.md "Calibration").
    r -= p.paranasalHollow * std::exp(-sq((ax - 25) / 14) - sq((Y + 12) / 21));
    // Temporal hollow: behind the orbit's lateral rim and above the zygomatic arch the temple lies
    // back (kTemporalHollow).
    r -= kTemporalHollow * std::exp(-sq((ax - (p.exex / 2 + 15)) / 10) - sq((Y - 6) / 16));
    r += p.chinHeight * std::exp(-sq(X / p.chinWidth) - sq((Y - f.yPg) / 12));
    // Mentolabial sulcus between the lower lip and the chin.
    r -= (1.5 + 0.3 * p.lowerLipFullness) * std::exp(-sq(X / 17) - sq((Y - lerp(f.ySto - p.lowerVermilion, f.yPg, 0.45)) / 5));
    (void)theta;
    return r;
}

// Which side of the mouth line a point is on, smoothly outside the mouth: 1 above, 0 below.
// `a` is the position across the mouth (-1 and 1 at the corners), b mm above the slit row.
double upperWeight(const Frame& f, double a, double b, int slit)
{
    // Outside the mouth a smooth step across the mouth line, leaning upwards so the corners
    // follow the jaw only a little; inside, a clean split along the slit that blends into the
    // outside step over the last 40% towards each corner (so corner triangles do not shear).
    const double band = 2.5 + 0.9 * std::max(0.0, (std::abs(a) - 1) * f.p.chch / 2);
    const double outside = smoothstep(-1.4 * band, 0.6 * band, b);
    if (std::abs(a) >= 1 - 1e-9)
        return outside;
    const bool upper = b > 1e-9 || (std::abs(b) <= 1e-9 && slit >= 0);
    const double corner = smoothstep(0.6, 1.0, std::abs(a));
    return upper ? 1 - corner * (1 - outside) : corner * outside;
}

// One lip's profile across it, as a fraction of its fullness: t is 0 at the slit and 1 at the
// vermilion border (h mm from the slit). The vermilion rises from a groove at the slit to its
// crest at t = crest and falls by `fall` to the border; beyond it the skin lip rolls on with the
// same slope and comes to rest w mm past the border (a cubic Hermite span: value and slope match
// at the border, both are 0 at its end), at the nose's base for the upper lip and in the
// mentolabial sulcus for the lower. `lateral` is set to the taper across the mouth that the
// profile is to be scaled by: the vermilion's own, blending into the skin lip's (see kShelfFade)
// over the span.
//
// v16 (docs/realism.md, "Now (4 December, v16)"): until v15 the vermilion fell to 0.7 (upper) or
// 0.55 (lower) at the border with a slope near 1 mm/mm and a flat shelf began there, a concave
// kink that drew a light line round each lip on the curvature maps, and the shelf ended 6-7 mm
// on, so each lip read as a slab with a rim. Now the upper lip is one convex mound from the slit
// to the nose, as ICT-FaceKit's mean face is.
struct LipShape {
    double crest, fall;
};
constexpr LipShape kUpperLip { 0.6, 0.08 }, kLowerLip { 0.55, 0.1 };

double lipProfile(const LipShape& lip, double t, double h, double w, double vermilionTaper, double shelfTaper, double& lateral)
{
    lateral = vermilionTaper;
    if (t < lip.crest)
        return -0.35 + 1.35 * (1 - sq(1 - t / lip.crest));
    if (t < 1)
        return 1 - lip.fall * sq((t - lip.crest) / (1 - lip.crest));
    const double s = (t - 1) * h;
    lateral = lerp(vermilionTaper, shelfTaper, smoothstep(0, w, s));
    if (s >= w)
        return 0;
    const double u = s / w, atBorder = 1 - lip.fall, slopeTimesW = -2 * lip.fall / ((1 - lip.crest) * h) * w;
    return atBorder * (2 * u * u * u - 3 * u * u + 1) + slopeTimesW * u * sq(1 - u);
}

// The nasolabial fold (v17): a crease from just above and outside the ala's widest point (1.5
// mm out, 2 mm above kFoldAt of the way from sn to prn) down and out to 8 mm beside and 6 mm
// below the mouth's corner, bowed kNasolabialBow mm outwards (a quadratic Bezier), with the cheek
// swelling beside it on the outside. Across it, at signed distance d mm
// (positive towards the cheek): depth (kNasolabialBulge e^-((d - 6)/6)^2 - e^-(d/3.5)^2), faded
// in over its first 15% and out over its last 20%. Until v16 the cheek ran into the upper lip
// as one plane, and the curvature maps had no line where ICT-FaceKit's mean face shows the fold
// (docs/realism.md, "Now (4 December, v17)"). ax, Y: the vertex in the neutral face, mm.
constexpr double kNasolabialBow = 4.0, kNasolabialBulge = 0.8;

double nasolabialFold(const Frame& f, double ax, double Y)
{
    const FaceParams& p = f.p;
    const NasolabialCurve& c = f.fold;
    if (p.nasolabialDepth <= 0)
        return 0;
    const Eigen::Vector2d q(ax, Y);
    if ((q.array() < c.lo.array()).any() || (q.array() > c.hi.array()).any())
        return 0;
    // Distance to the polyline; `along` runs 0..1 from its front to its back and on past either
    // end along the chord.
    double best = std::numeric_limits<double>::infinity(), along = 0, d = 0;
    for (int k = 1; k <= NasolabialCurve::kSegments; ++k) {
        const Eigen::Vector2d& prev = c.points[static_cast<size_t>(k - 1)];
        const Eigen::Vector2d e = c.points[static_cast<size_t>(k)] - prev;
        const double h = std::clamp((q - prev).dot(e) / e.squaredNorm(), 0.0, 1.0);
        const Eigen::Vector2d foot = prev + h * e;
        const double dd = (q - foot).squaredNorm();
        if (dd < best) {
            best = dd;
            along = (k - 1 + h) / NasolabialCurve::kSegments;
            d = ((q - foot).dot(Eigen::Vector2d(-e.y(), e.x())) >= 0 ? 1 : -1) * std::sqrt(dd);
        }
    }
    if (along <= 0)
        along = (q - c.points.front()).dot(c.along) / c.chord;
    else if (along >= 1)
        along = 1 + (q - c.points.back()).dot(c.along) / c.chord;
    const double fade = smoothstep(-0.1, 0.15, along) * (1 - smoothstep(0.8, 1.15, along));
    return p.nasolabialDepth * fade * (kNasolabialBulge * std::exp(-sq((d - 6) / 6)) - std::exp(-sq(d / 3.5)));
}

} // namespace

NasolabialCurve detail::nasolabialCurve(const Frame& f)
{
    const FaceParams& p = f.p;
    NasolabialCurve c;
    const Eigen::Vector2d a(p.alal / 2 + 1.5, lerp(f.ySn, f.yPrn, kFoldAt) + 2), b(p.chch / 2 + 8, f.ySto - 6);
    c.along = (b - a).normalized();
    c.chord = (b - a).norm();
    const Eigen::Vector2d out(-c.along.y(), c.along.x());
    const Eigen::Vector2d control = 0.5 * (a + b) + kNasolabialBow * out;
    constexpr double kReach = 20; // mm beyond which the fold adds nothing measurable
    c.lo = a.cwiseMin(b).cwiseMin(control).array() - kReach;
    c.hi = a.cwiseMax(b).cwiseMax(control).array() + kReach;
    c.points[0] = a;
    for (int k = 1; k <= NasolabialCurve::kSegments; ++k) {
        const double t = static_cast<double>(k) / NasolabialCurve::kSegments;
        c.points[static_cast<size_t>(k)] = sq(1 - t) * a + 2 * t * (1 - t) * control + sq(t) * b;
    }
    return c;
}

namespace {

// Soft tissue, evaluated where the vertex sits in the neutral face so it moves with the skin:
// lips, philtrum, cheeks, eyebrows, fine detail, and the pose's radial offsets.
double soft(const Frame& f, double theta0, double phi0, double X, double Y, int slit, const FaceActions& act)
{
    const FaceParams& p = f.p;
    const double ax = std::abs(X), half = p.chch / 2;
    const double b = midY(f, phi0) - f.ySto, a = theta0 / f.thetaCh;
    double r = 0;

    // Lips: vermilion bulges meeting in a groove at the slit, thinning to the corners; the skin
    // lip rolls on from each border (lipProfile) and fades smoothly inside the corners from
    // kShelfFade of the way out (until v13 it was scaled by the vermilion's taper all the way,
    // whose slope is infinite at the corners: vertical creases above and below them, a box round
    // the mouth; docs/realism.md, curvature maps). The vermilion ends at the corners with a crease
    // (the commissure). Its volume thins towards them as taper^lipTaper, a parameter of the face
    // (v16; 0.7 for every face until v15, which kept each lip nearly full height to within a few
    // mm of its corner, a crescent-ended slab from the front).
    const bool upper = b > 1e-9 || (std::abs(b) <= 1e-9 && slit >= 0);
    const double press = 1 - 0.55 * act.lipPress;
    // Both tapers are 0 from the corners out (|a| >= 1), so the lips add nothing there.
    const double taper = std::abs(a) < 1 ? std::sqrt(1 - a * a) : 0.0;
    const double vermilionTaper = std::pow(taper, p.lipTaper);
    const double shelfTaper = 1 - smoothstep(kShelfFade, 1, std::abs(a));
    const double snB = f.ySn - f.ySto;
    if (upper) {
        const double h = p.upperVermilion * (0.3 + 0.7 * taper)
            * (1 - 0.1 * p.cupidBow * std::exp(-sq(a / 0.09)) + 0.05 * p.cupidBow * std::exp(-sq((std::abs(a) - 0.22) / 0.1)));
        const double span = std::clamp(snB - h, kUpperSpanMin, kUpperSpanMax);
        double lateral;
        const double shape = lipProfile(kUpperLip, b / h, h, span, vermilionTaper, shelfTaper, lateral);
        r += p.upperLipFullness * press * lateral * shape;
    } else {
        const double h = p.lowerVermilion * (0.3 + 0.7 * taper);
        double lateral;
        const double shape = lipProfile(kLowerLip, -b / h, h, kLowerSpan, vermilionTaper, shelfTaper, lateral);
        r += (p.lowerLipFullness * press - act.lowerLipTuck) * lateral * shape;
    }
    r -= 1.0 * std::exp(-sq((ax - half) / 4) - sq(b / 4)); // commissure
    r += act.lipsForward * std::exp(-std::pow(X / (half + 4), 4) - std::pow((b + 1) / 13, 4));

    // Philtrum: a groove between two ridges from the vermilion border to the nose.
    const double window = smoothstep(p.upperVermilion * 0.9, p.upperVermilion * 1.3, b) * (1 - smoothstep(snB - 5, snB, b));
    r += p.philtrumDepth * window * (0.35 * std::exp(-sq((ax - 5) / 1.8)) - std::exp(-sq(X / 2.6)));

    r += nasolabialFold(f, ax, Y);
    // The subnasal ridge (face_frame.h), on the skin so that it moves with the upper lip.
    r += subnasalRidge(X, b - snB);

    // Cheeks, eyebrows, nose wrinkles.
    r += p.cheekFullness * std::exp(-sq((ax - (half + 17)) / 15) - sq((b - 12) / 16));
    r += act.cheekPuff * std::exp(-sq((ax - (half + 13)) / 14) - sq((b - 2) / 15));
    r += act.cheekRaise * std::exp(-sq((ax - (half + 12)) / 12) - sq((b - 24) / 11));
    const double browLateral = smoothstep(p.enen / 2 - 4, p.enen / 2 + 2, ax) * (1 - smoothstep(p.exex / 2 + 2, p.exex / 2 + 10, ax));
    r += 1.0 * browLateral * std::exp(-sq((Y - p.browHeight) / 3.5));
    r += 0.8 * act.noseWrinkle * std::exp(-sq((ax - 9) / 5) - sq((Y - (f.yN - 14)) / 7));

    for (const DetailBump& d : p.detail)
        r += d.height * std::exp(-(sq(theta0 - d.theta) + sq(phi0 - d.phi)) / sq(d.radius));
    // Shape fields, calmed over the lips, the nose and the eyes: lip corners, vermilion
    // borders, the nose tip and the eyeballs are placed by the parameters above, and a field's
    // slope there would tip the lips' rows past their corners, move the most forward point off
    // prn or shift the socket around its eyeball.
    // The population's mean fields (shapeFieldMeans) are calmed over all of the nose, whose
    // own parameters set its mean shape: 15% of a mean field's slope there tilts the flat
    // lobule so its most forward point leaves prn. A face's own variation keeps 15%.
    const auto [fields, meanFields] = shapeFieldSums(p.shapeModes, shapeFieldMeans(), theta0, phi0); // the face's own, the population's
    // The mean fields are calmed over a wider, softer window round the lips than a face's own
    // variation (v16): the mean fields stand well forward there (fitted without the lips), and
    // the variation's window, exp(-u^4 - v^4), rises so steeply 12 mm above the slit that the
    // mean fields' return drew a concave line across the skin lip just above the vermilion.
    const double lips = std::exp(-std::pow(X / (half + 6), 4) - std::pow(b / 12, 4));
    const double lipsMean = std::exp(-sq(X / (half + 10)) - sq(b / 16));
    const double nose = std::exp(-std::pow(X / 16, 4) - std::pow((Y - f.yPrn - 6) / 22, 4));
    const double eyes = std::exp(-std::pow((ax - f.xEye) / 25, 4) - std::pow((Y - 1) / 19, 4));
    // Under the chin the mean fields fade out from kUnderChinFrom to kUnderChinFrom +
    // kUnderChinOver rad below gn (v18). The lowest row of mean fields is -8.1 mm on the midline
    // and about 0 beside it; down to gn the profile's knots take the midline back out to its
    // targets, but below gn nothing does, so the fields left a trough along the midline under
    // the chin, and the mask's lower border (a grid row of one elevation) rose at the midline
    // between two low points: seen from the front, a wavy lower edge (1.42 mm on average over
    // the first 40 faces, up to 7.0; 0.66 and 4.9 mm now, the rest from each face's own fields,
    // which keep the spectrum's 15 modes and so stay). Faded from gn itself the chin's region
    // moves 1.56 mm RMS from ICT-FaceKit's (1.17 before): near gn ICT's face asks for what the
    // fields give (docs/realism.md, v18).
    const double underChin = smoothstep(f.phiGn - kUnderChinFrom, f.phiGn - kUnderChinFrom - kUnderChinOver, phi0);
    r += fields * (1 - std::max({ lips, 0.85 * nose, eyes })) + meanFields * (1 - std::max({ lipsMean, nose, eyes })) * (1 - underChin);
    return r;
}

// Radial distance along unit direction d (from the head's centre) at which the ray leaves
// ellipsoid `e`; for a ray that misses it, a continuation that falls `fall` semi-axes b per unit
// of the miss (in the ellipsoid's scaled space), so a smooth maximum with the skin has no step
// at the ellipsoid's silhouette as seen from the centre. `hit` tells which.
double ellipsoidExit(const Ellipsoid& e, const Eigen::Vector3d& d, double fall, bool* hit = nullptr)
{
    const Eigen::Vector3d o = -e.centre;
    const Eigen::Vector3d ol(o.dot(e.right) / e.a, o.dot(e.up) / e.b, o.dot(e.forward) / e.c);
    const Eigen::Vector3d dl(d.dot(e.right) / e.a, d.dot(e.up) / e.b, d.dot(e.forward) / e.c);
    const double dd = dl.squaredNorm();
    const double tc = -ol.dot(dl) / dd;
    const double m2 = (ol + tc * dl).squaredNorm();
    if (hit)
        *hit = m2 <= 1;
    if (m2 <= 1)
        return tc + std::sqrt((1 - m2) / dd);
    return tc - fall * (std::sqrt(m2) - 1) * e.b;
}

// The nose's tip dome (kTipDomeHalfWidth...): its front on the midline at the height the nose's
// radial profile gives prn. From f.noseTip, so it moves with the frame's solve for it.
Ellipsoid tipDome(const Frame& f)
{
    const Eigen::Vector3d prn = (rhoBase(f, 0, f.phiPrn) / std::cos(f.phiPrn) + f.noseTip) * direction(0, f.phiPrn);
    Ellipsoid dome;
    dome.right = Eigen::Vector3d::UnitX();
    dome.up = Eigen::Vector3d::UnitY();
    dome.forward = Eigen::Vector3d::UnitZ();
    dome.a = kTipDomeHalfWidth * f.p.tipWidth;
    // prn lies 6-8 mm above sn; the floor keeps the dome a dome on a face that has it lower.
    dome.b = kTipDomeHalfHeight * std::max(f.yPrn - f.ySn, 3.0);
    dome.c = kTipDomeDepth;
    dome.centre = prn - dome.c * dome.forward;
    return dome;
}

struct ChartPoint {
    double theta, phi;
    double jaw; // 0..1, how much of the jaw rotation this vertex follows
};

// Moves a vertex across the underlying structure: eyelids, brows, lips and lip corners.
ChartPoint warp(const Frame& f, double theta0, double phi0, int slit, bool eyeRow, const FaceActions& act)
{
    const FaceParams& p = f.p;
    double dTheta = 0, dPhi = 0;
    const int side = theta0 >= 0 ? 1 : 0; // index into [right, left]
    const double sign = theta0 >= 0 ? 1 : -1;
    const double R = f.rEye;

    // Eye: open the slit into an almond, tilt it, close or widen it, raise the lower lid.
    const double a = (std::abs(theta0) - f.thetaEn) / (f.thetaEx - f.thetaEn);
    const double b = phi0;
    const double tilt = p.canthalTilt / R * (a <= 0 ? 0 : a <= 1 ? a : 1 - smoothstep(1, 1.8, a));
    dPhi += tilt * (1 - smoothstep(0, 28 / R, std::abs(b)));
    if (a > 0 && a < 1) {
        const double shape = std::pow(std::sin(M_PI * a), 0.8);
        const double minGap = 0.5 / R * shape;
        double up = 0.58 * p.fissureHeight / R * shape * (1 + act.lidWide);
        const double lo0 = 0.42 * p.fissureHeight / R * shape;
        up -= act.lidClose[side] * (up + lo0 - minGap);
        const double lo = std::max(lo0 - act.lowerLidRaise / R * shape, minGap - up);
        const bool above = b > 1e-12 || (std::abs(b) <= 1e-12 && (slit >= 0 || !eyeRow));
        if (above)
            dPhi += up * fall(b / ((p.browHeight + 4) / R));
        else
            dPhi -= lo * fall(-b / (13 / R));
    }
    // Brows: inner and outer raise, lowering (with a pull towards the midline).
    const double q = smoothstep(-0.2, 1.2, a);
    const double lift = act.browInnerRaise * (1 - q) + act.browOuterRaise * q - act.browLower;
    const double vertical
        = smoothstep(3 / R, (p.browHeight + 10) / R, b) * (1 - smoothstep((p.browHeight + 12) / R, (p.browHeight + 45) / R, b));
    const double lateral = 1 - smoothstep(f.thetaEx + 5 / R, f.thetaEx + 30 / R, std::abs(theta0));
    dPhi += lift / R * vertical * lateral;
    dTheta -= sign * act.browLower * 0.25 / R * vertical * lateral * smoothstep(0, f.thetaEn, std::abs(theta0));

    // The alar lobules rise with a nose wrinkle (kAlaWrinkleLift), their skin with them: mm over
    // the chart's local mm per radian of elevation (Y = rho tan(phi)).
    if (act.noseWrinkle != 0) {
        const double rho0 = rhoBase(f, theta0, phi0);
        const double X0 = rho0 * std::sin(theta0), Y0 = rho0 * std::tan(phi0);
        const AlarLobule ala = alarLobule(f, 0);
        const double da = std::hypot((std::abs(X0) - ala.x) / ala.radius, (Y0 - ala.y) / (kAlaAbove * ala.radius));
        dPhi += kAlaWrinkleLift * act.noseWrinkle * sq(std::cos(phi0)) / rho0 * fall((da - kAlaSlideFrom) / (kAlaSlideTo - kAlaSlideFrom));
    }

    // Mouth. Positions in mm relative to the stomion at the neutral face.
    const double Rm = f.mouthScale;
    const double half = p.chch / 2, am = theta0 / f.thetaCh, X = am * half, bm = midY(f, phi0) - f.ySto;
    const double wu = upperWeight(f, am, bm, slit);
    // Skin pulled by the lip muscles must not climb onto the nose's steep base.
    const double belowNose = 1 - smoothstep(f.ySn - f.ySto - 16, f.ySn - f.ySto - 1, bm);
    if (std::abs(am) < 1 - 1e-9) {
        const double shape = std::pow(1 - am * am, 0.6);
        const double raise = lerp(act.upperLipRaise[0], act.upperLipRaise[1], smoothstep(-0.6, 0.6, am));
        const double gap = 0.25;
        const double up = (gap + 0.4 * act.lipPart + 0.6 * raise) / Rm * shape;
        const double lo = (gap + 0.6 * act.lipPart + act.lowerLipDepress) / Rm * shape;
        dPhi += wu * up * fall(std::max(bm, 0.0) / ((f.ySn - f.ySto) * 0.8)) * belowNose - (1 - wu) * lo * fall(std::max(-bm, 0.0) / 16);
    }
    for (int s = 0; s < 2; ++s) {
        const double sx = s == 1 ? 1 : -1;
        const double k = std::exp(-sq((X - sx * half) / 16) - sq(bm / 16)) * belowNose;
        dPhi += (0.5 * act.cornerPull[s] - act.cornerDepress[s]) / Rm * k;
        dTheta += sx * (0.8 * act.cornerPull[s] + act.mouthStretch) / f.rMouth * k;
        dPhi += wu * act.upperLipRaise[s] / Rm * std::exp(-sq((X - sx * half / 2) / 12) - sq((bm - 6) / 9)) * belowNose;
    }
    dTheta -= 0.35 * act.pucker * theta0 * std::exp(-std::pow(X / (half + 10), 4) - std::pow(bm / 18, 4)) * belowNose;

    // Jaw: everything below the mouth line follows (the mask ends just under the chin, so the
    // submental skin moves with the mandible), fading out towards the ears.
    double jaw = 1 - wu;
    jaw *= 1 - smoothstep(0.8, 1.75, std::abs(theta0));
    return { theta0 + dTheta, phi0 + dPhi, jaw };
}

// Everything about one vertex's skin radius.
double skinRadius(
    const Frame& f, double theta, double phi, double theta0, double phi0, int slit, const FaceActions& act, bool eyeMargin = false)
{
    const double rho = rhoBase(f, theta, phi);
    const double X = rho * std::sin(theta), Y = rho * std::tan(phi);
    const double rho0 = rhoBase(f, theta0, phi0);
    const double X0 = rho0 * std::sin(theta0), Y0 = rho0 * std::tan(phi0);
    double face = rho / std::cos(phi) + bone(f, theta, phi, X, Y, act) + soft(f, theta0, phi0, X0, Y0, slit, act);
    const Eigen::Vector3d d = direction(theta, phi);
    face = smax(face, ellipsoidExit(tipDome(f), d, kTipDomeFall), kTipDomeBlend);
    // The radial distance at which the lid must stay above the eyeball behind it.
    bool hit = false;
    const double cover = ellipsoidExit(f.eye[theta >= 0 ? 1 : 0], d, 6.0, &hit);
    // A lid margin rests on the eyeball wherever one is behind it, so no gap opens between
    // lid and eye when seen from the side.
    if (eyeMargin && hit)
        return cover + 0.6;
    // Elsewhere the lid is thicker than at its margin, which also keeps the chords of coarse
    // triangles clear of the eyeball.
    return smax(face, cover + (eyeMargin ? 0.6 : 1.2), 1.0);
}

// How far vertex (theta0, phi0) of the neutral chart moves, from its neutral position, into its
// nostril's vestibule: zero outside the footprint. The one displacement of the skin that is not
// radial (a radial height cannot turn up into the nose). Its direction points back more than up
// (kVestibuleBack): pointing further up folds the pocket's front wall (the face_shape tests check
// for folds, docs/realism.md).
Eigen::Vector3d vestibule(const Frame& f, double theta0, double phi0)
{
    const FaceParams& p = f.p;
    const double ax = std::abs(rhoBase(f, theta0, phi0) * std::sin(theta0));
    const double ex = (ax - kNostrilOut * f.xAl) / (kNostrilHalfWidth * p.nostrilSize);
    const double ep = (phi0 - lerp(f.phiSn, f.phiPrn, kNostrilAt)) / (kNostrilHalfHeight * (f.phiPrn - f.phiSn));
    const double rho = std::hypot(ex, ep);
    const double wanted = rho >= 1
        ? 0.0
        : kVestibuleDepth * (1 - smoothstep(kVestibuleFloor, 1, rho)) * smoothstep(kColumellaHalf, kColumellaHalf + kColumellaBlend, ax);
    if (wanted <= 0) // outside the footprint, or on the columella
        return Eigen::Vector3d::Zero();
    const Eigen::Vector3d x0 = neutralRadius(f, theta0, phi0) * direction(theta0, phi0);
    const Eigen::Vector3d dir = Eigen::Vector3d(0, 1, -kVestibuleBack).normalized();
    // The room: how far along dir the ray stays inside the neutral skin (1 mm steps, then
    // bisection to 0.01 mm; a 0.1 mm march made `bench synth` twice as slow).
    auto inside = [&](double t) {
        const Eigen::Vector3d q = x0 + t * dir;
        return q.norm() < neutralRadius(f, std::atan2(q.x(), q.z()), std::atan2(q.y(), std::hypot(q.x(), q.z())));
    };
    double exit = wanted + kVestibuleWall; // only the room up to the depth wanted matters
    for (double step = std::min(1.0, exit), last = 0.0; last < exit; last = step, step = std::min(step + 1, exit))
        if (!inside(step)) {
            double lo = last, hi = step;
            while (hi - lo > 0.01)
                (inside((lo + hi) / 2) ? lo : hi) = (lo + hi) / 2;
            exit = hi;
            break;
        }
    return std::min(std::max(0.0, exit - kVestibuleWall), wanted) * dir;
}

} // namespace

Eigen::Vector3d detail::alaSpread(const Frame& f, double theta0, double phi0)
{
    const double rho0 = rhoBase(f, theta0, phi0);
    const double ax = std::abs(rho0 * std::sin(theta0)), Y = rho0 * std::tan(phi0);
    const AlarLobule ala = alarLobule(f, 0);
    const double d2 = (sq(ax - ala.x) + sq(Y - ala.y)) / sq(kAlaSpreadRadius * ala.radius);
    if (d2 >= 1)
        return Eigen::Vector3d::Zero();
    return Eigen::Vector3d((theta0 >= 0 ? 1 : -1) * kAlaSpread * sq(1 - d2), 0, 0);
}

double detail::neutralRadius(const Frame& f, double theta, double phi)
{
    return skinRadius(f, theta, phi, theta, phi, 0, FaceActions {});
}

namespace {

// Piecewise-linear map from column offset to azimuth through (offset, angle) knots.
double columnTheta(const std::vector<std::pair<double, double>>& knots, double s)
{
    const double as = std::abs(s);
    for (size_t i = 0; i + 1 < knots.size(); ++i)
        if (as <= knots[i + 1].first) {
            const double t = (as - knots[i].first) / (knots[i + 1].first - knots[i].first);
            return (s < 0 ? -1 : 1) * lerp(knots[i].second, knots[i + 1].second, t);
        }
    return (s < 0 ? -1 : 1) * knots.back().second;
}

} // namespace

Vertices synthesizeFace(const FaceTopology& t, const FaceParams& params, const FaceActions& act)
{
    const Frame f = makeFrame(params);
    const int half = t.mid;
    const std::vector<std::pair<double, double>> eyeKnots = { { 0, 0 }, { t.sEn, f.thetaEn }, { t.sEx, f.thetaEx }, { half, kSide } };
    const std::vector<std::pair<double, double>> noseKnots = { { 0, 0 }, { t.sEn, f.thetaAl }, { t.sEx, f.thetaEx }, { half, kSide } };
    const std::vector<std::pair<double, double>> mouthKnots = { { 0, 0 }, { t.sCh, f.thetaCh }, { t.sEx, f.thetaEx }, { half, kSide } };
    const std::vector<double> phiKnots = { 0, f.phiBrow, f.phiN, 0, f.phiPrn, f.phiSn, f.phiLs, f.phiSto, f.phiLi, f.phiPg, f.phiGn, 0 };
    const auto& K = t.rowKnot;

    auto chart = [&](int row, int col) {
        const double s = col - t.mid;
        const double te = columnTheta(eyeKnots, s), tn = columnTheta(noseKnots, s), tm = columnTheta(mouthKnots, s);
        double theta;
        if (row <= K[3])
            theta = te;
        else if (row <= K[4])
            theta = lerp(te, tn, double(row - K[3]) / (K[4] - K[3]));
        // The upper lip, from the ls row down to the slit, keeps the mouth's columns; the blend
        // to the nose's columns happens above it. Blended down to the slit, the columns fanned
        // outwards up the lip, and the outer lip line's vertex one column in from a corner
        // could reach past ch (by up to 0.08 mm, seed 7; docs/realism.md).
        else if (row <= K[6])
            theta = lerp(tn, tm, double(row - K[4]) / (K[6] - K[4]));
        else
            theta = tm;
        const double side = smoothstep(0.5, 1.6, std::abs(theta));
        // At the sides the top row stays at least 0.12 rad above the brow row, so faces with
        // high brows keep their top rows in order.
        const double top = lerp(f.phiTopFront, std::max(0.42, f.phiBrow + 0.12), side);
        const double bottom = lerp(f.phiBottomFront, std::min(-1.0, f.phiGn - 0.15), smoothstep(0.4, 1.3, std::abs(theta)));
        double phi;
        if (row <= K[1])
            phi = lerp(top, f.phiBrow, double(row) / K[1]);
        else if (row >= K[10])
            phi = lerp(f.phiGn, bottom, double(row - K[10]) / (K[11] - K[10]));
        else {
            size_t k = 1;
            while (row > K[k + 1])
                ++k;
            phi = lerp(phiKnots[k], phiKnots[k + 1], double(row - K[k]) / (K[k + 1] - K[k]));
        }
        return std::pair<double, double>(theta, phi);
    };

    Vertices V(t.labels.vertexCount, 3);
    const Eigen::Vector3d pivot(0, -22, f.zf - 88);
    const double jawAngle = act.jawOpen * M_PI / 180;
    auto jawMove = [&](const Eigen::Vector3d& x, double weight) -> Eigen::Vector3d {
        const double angle = jawAngle * weight;
        const Eigen::Vector3d rel = x - pivot;
        const double c = std::cos(angle), s = std::sin(angle);
        // Rotation about +x moving the chin down and back, plus the condyles' forward glide.
        const Eigen::Vector3d turned(rel.x(), rel.y() * c - rel.z() * s, rel.y() * s + rel.z() * c);
        return turned + pivot + Eigen::Vector3d(0, 0, 0.35 * angle * 40);
    };

    // Skin vertex i in actions a; the jaw turns by the pose's angle, so only for the pose itself.
    auto skinPoint = [&](size_t i, const FaceActions& a, bool turnJaw) -> Eigen::Vector3d {
        const SkinVertex& sv = t.skin[i];
        const auto [theta0, phi0] = chart(sv.row, sv.col);
        const ChartPoint cp = warp(f, theta0, phi0, sv.slit, sv.row == K[3], a);
        const double r = skinRadius(f, cp.theta, cp.phi, theta0, phi0, sv.slit, a, sv.slit != 0 && sv.row == K[3]);
        const Eigen::Vector3d x = r * direction(cp.theta, cp.phi);
        return (turnJaw ? jawMove(x, cp.jaw) : x) + vestibule(f, theta0, phi0) + alaSpread(f, theta0, phi0);
    };
    for (size_t i = 0; i < t.skin.size(); ++i)
        V.row(static_cast<Eigen::Index>(i)) = skinPoint(i, act, true).transpose();

    // Eyeballs: UV ellipsoids in each eye's frame, poles along its up axis.
    const Component* eyes[2] = { t.labels.component("eye_right"), t.labels.component("eye_left") };
    for (int s = 0; s < 2; ++s) {
        const Ellipsoid& e = f.eye[s];
        int v = eyes[s]->begin;
        // The mesh sits 0.6 mm inside the ellipsoid the lids rest on, so even coarse lid
        // triangles (whose chords sag towards the eye) keep clear of it.
        const double a = e.a - 0.6, b = e.b - 0.6, c = e.c - 0.6;
        auto put = [&](double polar, double azimuth) {
            const Eigen::Vector3d x = e.centre + a * std::sin(polar) * std::sin(azimuth) * e.right + b * std::cos(polar) * e.up
                + c * std::sin(polar) * std::cos(azimuth) * e.forward;
            V.row(v++) = x.transpose();
        };
        put(0, 0);
        for (int i = 1; i <= t.eyeRings; ++i)
            for (int j = 0; j < t.eyeSegments; ++j)
                put(M_PI * i / (t.eyeRings + 1), 2 * M_PI * j / t.eyeSegments);
        put(M_PI, 0);
    }

    // Dental arches: tubes along a parabola a few mm behind the lips; the lower arch and the
    // tongue follow the jaw.
    const double zFront = f.depth(f.phiSto) - 4.0;
    const double yOcclusal = f.ySto - 0.5;
    const double archHalf = 21 + 0.1 * (params.jawWidth - 100), archDepth = 30;
    double lowerShift = 0; // how far a retruded chin pushed the lower arch back (<= 0)
    for (int lower = 0; lower < 2; ++lower) {
        const Component* c = t.labels.component(lower ? "teeth_lower" : "teeth_upper");
        const double scale = lower ? 0.94 : 1.0;
        // Short or retruded chins: the lower incisors stay above the chin and behind its skin.
        const double height = lower ? std::clamp(yOcclusal - 0.7 - (f.yPg + 4), 5.0, 8.5) : 9.5;
        const double yMid = lower ? yOcclusal - 0.7 - height / 2 : yOcclusal + 0.7 + height / 2;
        double zArch = zFront - (lower ? 1.5 : 0);
        if (lower) {
            double lo = f.phiGn, hi = f.phiSto; // elevation of the lower teeth's bottom on the midline
            for (int k = 0; k < 50; ++k) {
                const double m = (lo + hi) / 2;
                (midY(f, m) < yMid - height / 2 ? lo : hi) = m;
            }
            zArch = std::min(zArch, f.depth(lo) - 4.0);
            lowerShift = zArch - (zFront - 1.5);
        }
        std::vector<Eigen::Vector3d> points;
        for (int i = 0; i < t.archSamples; ++i) {
            const double u = -1 + 2.0 * i / (t.archSamples - 1);
            const double thick = lerp(6.0, 9.5, u * u);
            const Eigen::Vector3d centre(scale * archHalf * u, yMid, zArch - thick / 2 - archDepth * u * u);
            const Eigen::Vector3d tangent = Eigen::Vector3d(scale * archHalf, 0, -2 * archDepth * u).normalized();
            const Eigen::Vector3d normal = Eigen::Vector3d(0, 1, 0).cross(tangent).normalized();
            for (int j = 0; j < t.archSection; ++j) {
                const double g = 2 * M_PI * j / t.archSection;
                // A rounded box: superellipse section, taller than thick.
                const double cg = std::cos(g), sg = std::sin(g);
                const double cy = std::copysign(std::pow(std::abs(cg), 0.6), cg), sz = std::copysign(std::pow(std::abs(sg), 0.6), sg);
                points.push_back(centre + height / 2 * cy * Eigen::Vector3d(0, 1, 0) + thick / 2 * sz * normal);
            }
        }
        auto centreAt = [&](int i) {
            Eigen::Vector3d m = Eigen::Vector3d::Zero();
            for (int j = 0; j < t.archSection; ++j)
                m += points[static_cast<size_t>(i * t.archSection + j)];
            return Eigen::Vector3d(m / t.archSection);
        };
        std::vector<Eigen::Vector3d> all;
        all.push_back(centreAt(0) - 0.8 * (centreAt(1) - centreAt(0)).normalized());
        all.insert(all.end(), points.begin(), points.end());
        const int last = t.archSamples - 1;
        all.push_back(centreAt(last) + 0.8 * (centreAt(last) - centreAt(last - 1)).normalized());
        for (size_t k = 0; k < all.size(); ++k) {
            const Eigen::Vector3d x = lower ? jawMove(all[k], 1.0) : all[k];
            V.row(c->begin + static_cast<Eigen::Index>(k)) = x.transpose();
        }
    }

    // Tongue: a flattened ellipsoid lying in the lower arch, its tip narrowed.
    const Component* tongue = t.labels.component("tongue");
    const Eigen::Vector3d tongueCentre(
        0, yOcclusal - 8 + std::min(act.tongueUp, 3.0), zFront - 28 + lowerShift + std::min(act.tongueForward, 2.5));
    int v = tongue->begin;
    auto putTongue = [&](double polar, double azimuth) {
        const double z = std::sin(polar) * std::cos(azimuth);
        const double narrow = 1 - 0.3 * std::max(0.0, z);
        const Eigen::Vector3d local(10.5 * narrow * std::sin(polar) * std::sin(azimuth), 5.0 * std::cos(polar), 16.5 * z);
        V.row(v++) = jawMove(tongueCentre + local, 1.0).transpose();
    };
    putTongue(0, 0);
    for (int i = 1; i <= t.tongueRings; ++i)
        for (int j = 0; j < t.tongueSegments; ++j)
            putTongue(M_PI * i / (t.tongueRings + 1), 2 * M_PI * j / t.tongueSegments);
    putTongue(M_PI, 0);
    // The face's place in the frame (kLandmarkCentre, kDriftKept), from its neutral landmarks
    // whatever the pose, so a pose moves its skin against the face's neutral, not its own
    // landmarks.
    const FaceActions rest {};
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& [name, v] : t.labels.landmarks) {
        if (v < 0 || static_cast<size_t>(v) >= t.skin.size())
            fail("synthesizeFace: landmark ", name, " (vertex ", v, ") is not a skin vertex");
        centroid += skinPoint(static_cast<size_t>(v), rest, false);
    }
    centroid /= static_cast<double>(t.labels.landmarks.size());
    const Eigen::Vector3d drift = centroid - Eigen::Vector3d(kLandmarkCentre[0], kLandmarkCentre[1], kLandmarkCentre[2]);
    V.rowwise() -= drift.cwiseProduct(Eigen::Vector3d(1 - kDriftKept[0], 1 - kDriftKept[1], 1 - kDriftKept[2])).transpose();
    return V;
}

} // namespace facesketch::dataset
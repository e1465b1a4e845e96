#include "dataset/synth/face_params.h"

#include "core/error.h"
#include "core/random.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

namespace facesketch::dataset {

const std::vector<Norm>& farkasNorms()
{
    // Farkas LG, Anthropometry of the Head and Face, 2nd ed., 1994: North American Caucasian
    // adults (19-25 years), mean and SD in mm, men then women.
    static const std::vector<Norm> norms = {
        { "ex-ex", "ex_r", "ex_l", 91.2, 3.0, 87.8, 3.2 }, // biocular width
        { "en-en", "en_r", "en_l", 33.3, 2.7, 31.8, 2.3 }, // intercanthal width
        { "al-al", "al_r", "al_l", 34.9, 2.1, 31.4, 2.0 }, // nose width
        { "ch-ch", "ch_r", "ch_l", 53.3, 3.3, 49.8, 3.2 }, // mouth width
        { "n-gn", "n", "gn", 121.3, 6.8, 112.8, 5.2 },     // morphological face height
        { "n-sn", "n", "sn", 54.8, 3.3, 50.6, 3.1 },       // nose height
        { "sn-sto", "sn", "sto", 22.3, 2.3, 19.9, 2.0 },   // upper lip height
    };
    return norms;
}

namespace {

double sq(double x)
{
    return x * x;
}

// One Farkas measure with the shared size factor g (see face_params.h).
double normDraw(const Norm& n, bool female, double g, double z)
{
    const double mean = female ? n.meanFemale : n.meanMale;
    const double sd = female ? n.sdFemale : n.sdMale;
    constexpr double rho = 0.45;
    return mean + sd * (rho * g + std::sqrt(1 - rho * rho) * z);
}

// Means (mm) of the 28 symmetric shape fields, row by row from the forehead down, columns 0-3
// from the midline out (shapeField): the smooth part of the ICT-FaceKit mean face the
// parameters cannot reach, fitted with the parameter means (sampleFaceParams, "ICT"), and
// refitted alone in v14 with the arched brow ridge and the temporal hollow (face_shape.cpp).
// v21 refitted the rows from the brows to the chin with the lower nose, mouth and chin
// (sampleFaceParams); v20's were 3.4 2.1 2.0 -0.1, 7.8 -10.9 -1.4 0.7, 1.3 3.1 -2.5 1.2,
// 11.8 -1.8 1.2 -0.2 and 2.1 -1.7 4.8 0.3.
constexpr double kFieldMeans[28] = {
    0.6, 0.6, -2.2, -2.8,   // forehead
    2.75, 2.1, 2.0, 1.2,    // brows
    8.45, -13.5, -0.1, 0.7, // eyes
    3.25, 1.8, -3.15, 1.85, // nose, upper cheeks
    14.4, -3.1, 1.85, -0.2, // mouth, lower cheeks
    0.15, 0.25, 7.4, 2.25,  // chin, jaw
    -8.1, 0.3, 0.4, 0.6,    // under the chin
};

// Face-wide factors (v15): every parameter drawn below and every symmetric shape field shares
// kFactorWeight of its standard normal with kFaceFactors factors of the face, each through its
// own fixed direction of loadings (a row of factorLoadings()). Real faces are built that way:
// ICT-FaceKit's nose alone predicts the rest of the face to 0.36 of the mean face's error,
// v14's (independent features and local fields) to 0.60 (`facesketch eval observe --region
// nose`, docs/realism.md "Now (4 December, v15)"). The loadings are random directions, fixed by
// a seed: which features vary together is not measured here, only how much, and weight 0.7
// (about half of every variance shared) was chosen by those region predictions with the
// spectrum kept at issue 16's 15 / 35 modes.
constexpr int kFaceFactors = 6;
constexpr double kFactorWeight = 0.7;
constexpr size_t kLoadingRows = 96; // the draws of one face that share the factors, at most

using Loadings = std::array<double, kFaceFactors>;

const std::vector<Loadings>& factorLoadings()
{
    static const std::vector<Loadings> rows = [] {
        Random random(20261204);
        std::vector<Loadings> r(kLoadingRows);
        for (Loadings& row : r) {
            double norm = 0;
            for (double& x : row) {
                x = random.normal();
                norm += x * x;
            }
            for (double& x : row)
                x /= std::sqrt(norm);
        }
        return r;
    }();
    return rows;
}

/// A face's factors and the standard normals that share them, in draw order.
class FaceFactors {
public:
    FaceFactors(std::uint64_t seed, int index)
    {
        // Their own stream, so the face's other draws are those of v14 (a paired comparison).
        Random random(splitMix64(seed * 31 + 0xABCDEF + 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(index)));
        for (double& u : factors_)
            u = random.normal();
    }

    /// z's share of the next loadings row: sqrt(1 - w^2) z + w (l . u), unit variance.
    double mix(double z)
    {
        if (next_ >= kLoadingRows)
            fail("sampleFaceParams: more than ", kLoadingRows, " draws share the face-wide factors");
        const Loadings& l = factorLoadings()[next_++];
        double shared = 0;
        for (int j = 0; j < kFaceFactors; ++j)
            shared += l[static_cast<size_t>(j)] * factors_[static_cast<size_t>(j)];
        return std::sqrt(1 - sq(kFactorWeight)) * z + kFactorWeight * shared;
    }

private:
    std::array<double, kFaceFactors> factors_ {};
    size_t next_ = 0;
};

} // namespace

FaceParams sampleFaceParams(std::uint64_t seed, int index)
{
    // A separate stream per identity: SplitMix64 of the index-th step of its Weyl sequence.
    Random rng(splitMix64(seed + 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(index)), BoxMuller::RedrawZero);

    FaceParams p;
    p.female = rng.uniform() < 0.5;
    p.age = rng.uniform(20, 65);
    const double g = rng.normal();
    const double s = p.female ? 1.0 : 0.0;               // 1 for women
    const double aging = std::max(0.0, p.age - 30) / 35; // 0 young .. 1 at 65

    FaceFactors factors(seed, index);
    const auto& norms = farkasNorms();
    auto draw = [&](int i) { return normDraw(norms[static_cast<size_t>(i)], p.female, g, factors.mix(rng.normal())); };
    p.exex = draw(0);
    p.enen = draw(1);
    p.alal = draw(2);
    p.chch = draw(3);
    p.ngn = draw(4);
    p.nsn = draw(5);
    p.snsto = draw(6);

    auto n = [&](double mean, double sd) { return mean + sd * factors.mix(rng.normal()); };
    // Means marked "ICT" were moved towards the ICT-FaceKit mean face (issue 16; docs/realism.md,
    // "Calibration"). First by hand, by the mean-face distance of `facesketch eval realism`
    // against an ICT import and the signed map of tools/realism-landmarks.py --map; then (3
    // December) together with kFieldMeans (above) by a regularised Gauss-Newton fit of all these
    // means to that distance (docs/realism.md, "Now (3 December, later)"), each move penalised by its
    // size in SDs so none goes far from the population it describes; refitted the same way around
    // the nostril vestibules (3 December, night), with the tip's and the lips' means held (moved,
    // the lips broke the HMM's reading of the upper lip). The Farkas draws above are
    // anthropometric norms and were left alone.
    // v20: 3.9 mm less, as sn moved forward onto the subnasal ridge (face_frame.h) and prn stayed.
    // v21: with the nose, mouth and chin 6 mm lower under the eyes (kNasionLowering, face_frame.cpp)
    // nine of these means and 16 of the mean fields were refitted to the mean-face distance by
    // coordinate descent (120 faces, steps of 0.5 then 0.25 SD, each move charged 0.005 mm^2
    // per SD^2; two rounds; docs/realism.md "v21"); their v20 values close each comment. The
    // first round also set the eyes 0.6 mm less deep (eyeSet), which turned the upper lids'
    // triangles over in the eye poses of many faces, so eyeSet stayed.
    p.tipProtrusion = n(20.4 - 1.5 * s, 1.8); // ICT: 20.5 before, then 22.5 until v19, 18.6 in v20
    p.tipRise = n(10.0 - 1.5 * aging, 1.2);   // ICT: 4.5 before (prn was 7 mm too near sn), 8.5 until v20
    p.dorsumHump = n(1.18 - 0.5 * s, 0.9);    // ICT: 0.6, then 0.8, then 0.6, then 0.5 before
    p.bridgeWidth = n(7.4 - 0.5 * s, 0.6);    // ICT: 6.5, then 7.2, then 7.3 before
    p.tipWidth = n(7.0 - 0.6 * s, 0.7);       // ICT: 8.8, then 5.8, then 6.3, then 6.9 before
    p.alaSize = n(5.9 - 0.5 * s, 0.5);        // ICT: 7.0, then 6.0, then 5.7 before
    p.nostrilSize = n(4.32 - 0.3 * s, 0.4);   // ICT: 3.6, then 3.7, then 4.14 before
    p.nasionDepth = n(-1.1 - 0.5 * s, 1.2);   // ICT: 3.0, then 0.4, then -0.3, then -0.5 before

    p.upperVermilion = n(10.4 - 0.4 * s - 1.5 * aging, 1.2); // ICT: 8.7 before
    p.lowerVermilion = n(10.2 - 0.5 * s - 1.5 * aging, 1.3); // ICT: 10.0 before
    p.upperLipFullness = n(6.6 - 1.5 * aging, 0.8);          // ICT: 5.6 before
    p.lowerLipFullness = n(5.8 - 1.5 * aging, 0.9);          // ICT: 6.2 before
    p.lipProtrusion = n(0.0, 1.2);                           // ICT: 2.0 before
    p.cupidBow = n(1.0, 0.3);
    p.philtrumDepth = n(0.9, 0.25);
    p.cornerHeight = n(0.0 - 1.0 * aging, 0.8);

    p.fissureHeight = n(10.4 - 1.2 * aging, 0.8); // ICT: 10.8, then 11.1, then 10.6 before
    p.canthalTilt = n(4.8 + 0.5 * s, 1.0);        // ICT: 2.0, then 3.8, then 4.6 before
    p.eyeSet = n(3.4, 1.2);                       // ICT: 6.5, then 3.1, then 3.3 before
    p.browRidge = n(4.47 - 2.0 * s, 0.9);         // ICT: 4.0, then 3.4, then 3.7, then 3.8 before
    p.browHeight = n(30.5 + 2.0 * s, 2.0);        // ICT: 17.0, then 25.0, then 30.0, then 31.2, then 31.5 before

    p.faceDepth = n(83.5 - 3.0 * s, 3.0) + 1.5 * g;        // ICT: 88.0, then 86.2, then 85.2, then 85.0 before
    p.foreheadSlope = n(14.0 - 4.0 * s, 4.0);              // ICT: 8.0, then 10.8, then 13.0 before
    p.headBreadth = n(156.7 - 7.0 * s, 5.0) + 2.0 * g;     // ICT: 154.0, then 154.4, then 155.6 before
    p.cheekboneWidth = n(138.7 - 8.2 * s, 5.3) + 2.0 * g;  // ICT: 139.1, then 139.0, then 138.8 before
    p.cheekboneHeight = n(0.3, 1.0);                       // ICT: 3.5, then 0.5 before
    p.cheekFullness = n(2.2 - 1.5 * aging + 0.5 * s, 1.0); // ICT: 2.5, then 2.3 before
    p.jawWidth = n(108.2 - 7.4 * s, 5.5) + 2.0 * g;        // ICT: 104.0, then 107.1, then 107.9 before
    p.jawAngle = n(-0.37 - 0.5 * s, 0.4);                  // ICT: 0.3, then 0.0, then -0.22 before
    p.chinProjection = n(-1.3 - 1.0 * s, 3.0);             // ICT: -2.0, then 0.2, then 0.1, then 0.2 before
    p.chinWidth = n(13.9 - 1.5 * s, 1.8);                  // ICT: 15.0, then 14.7, then 14.2 before
    p.chinHeight = n(4.4 - 0.8 * s, 0.8);                  // ICT: 2.5, then 3.3, then 4.2, then 4.6 before
    p.neckWidth = n(113.7 - 15.0 * s, 6.0);                // ICT: 115.0, then 114.8, then 114.0 before

    // Fine detail: a few low bumps spread over the face, so no two faces are smooth copies.
    for (int i = 0; i < 14; ++i) {
        DetailBump b;
        b.theta = rng.uniform(-0.9, 0.9);
        b.phi = rng.uniform(-0.85, 0.75);
        b.radius = rng.uniform(0.06, 0.16);
        // 0.45 until v14: with the face-wide factors sharing half the variance, the set needs
        // more small independent variation to keep 15 / 35 modes.
        b.height = 0.7 * rng.normal();
        p.detail.push_back(b);
    }

    // Shape fields, the face's own variation about the population's mean fields (kFieldMeans):
    // symmetric ones share a factor per lattice row and the face-wide factors; antisymmetric
    // ones are independent and smaller (faces are nearly symmetric). v19 (wider bumps, faces
    // placed as ICT-FaceKit's are, face_generator.h): 2.2 and 0.7 mm keep the spectrum's 15 / 35
    // modes, and the antisymmetric share of the set's variation over the central face is 1.6%,
    // ICT-FaceKit's 1.6%; until v18 2.9 and 1.4 mm on 0.2 rad bumps (docs/realism.md, "v19").
    double rowFactor[7];
    for (double& u : rowFactor)
        u = rng.normal();
    constexpr double kSymmetricSd = 2.2, kAsymmetricSd = 0.7, kRowWeight = 0.5;
    p.shapeModes.resize(kShapeFields);
    for (int k = 0; k < kShapeFields; ++k) {
        const double z = k < 28 ? factors.mix(rng.normal()) : rng.normal();
        p.shapeModes[static_cast<size_t>(k)]
            = k < 28 ? kSymmetricSd * (kRowWeight * rowFactor[k / 4] + std::sqrt(1 - sq(kRowWeight)) * z) : kAsymmetricSd * z;
    }
    // Drawn last so the parameters above keep their draws from before it was added (issue 16).
    p.paranasalHollow = n(6.0, 1.0); // ICT: 4.5, then 5.7 before
    // v16, drawn last for the same reason: lips full nearly to their corners (low) or thinning
    // early (high); at least 1, a little above v15's 0.7 for every face, whose lips ended at
    // the corners almost full height.
    p.lipTaper = std::max(1.0, n(2.5, 0.5));
    // v17: deeper with age, as on real faces (Farkas does not measure it): 0.6 mm at 30, 1.1 at
    // 65, spread 0.2. Twice that read better in the renders, but took the thesis' nearest-
    // candidate mapping from the front past its bar (contour_eval's test: 0.762 of the mean face's
    // error against 0.75; 0.742 at this depth, 0.744 without the fold): the crease is a contour
    // of every training face, beside the lines a stroke traces (docs/realism.md, v17).
    p.nasolabialDepth = std::max(0.0, n(0.6 + 0.5 * aging, 0.2));
    return p;
}

namespace {

/// Field k's place on the lattice (face_params.h): its row and column, and whether it is
/// symmetric. Antisymmetric fields use the off-midline columns 1..3 of each row.
struct FieldCell {
    int row, col;
    bool symmetric;
};

FieldCell fieldCell(int k)
{
    const bool symmetric = k < 28;
    return { symmetric ? k / 4 : (k - 28) / 3, symmetric ? k % 4 : 1 + (k - 28) % 3, symmetric };
}

} // namespace

double shapeField(int k, double theta, double phi, double width)
{
    const auto [row, col, symmetric] = fieldCell(k);
    const double phiC = 0.55 - 0.25 * row, thetaC = 0.3 * col;
    const double dPhi = sq(phi - phiC);
    const double right = std::exp(-(sq(theta + thetaC) + dPhi) / sq(width));
    if (col == 0)
        return right;
    const double left = std::exp(-(sq(theta - thetaC) + dPhi) / sq(width));
    return symmetric ? left + right : left - right;
}

const std::vector<double>& shapeFieldMeans()
{
    static const std::vector<double> means = [] {
        std::vector<double> m(kShapeFields, 0.0);
        std::copy(std::begin(kFieldMeans), std::end(kFieldMeans), m.begin());
        return m;
    }();
    return means;
}

namespace {

// The 49 fields at (theta, phi) for bumps of one width: each bump is exp(-dtheta^2 / w^2)
// exp(-dphi^2 / w^2), so row and column factors (14 distinct exponentials) give all of them.
std::array<double, kShapeFields> shapeFieldValues(double theta, double phi, double width)
{
    double row[7], right[4], left[4];
    for (int j = 0; j < 7; ++j)
        row[j] = std::exp(-sq(phi - (0.55 - 0.25 * j)) / sq(width));
    for (int c = 0; c < 4; ++c) {
        right[c] = std::exp(-sq(theta + 0.3 * c) / sq(width));
        left[c] = std::exp(-sq(theta - 0.3 * c) / sq(width));
    }
    std::array<double, kShapeFields> values;
    for (int k = 0; k < kShapeFields; ++k) {
        const auto [r, c, symmetric] = fieldCell(k);
        values[static_cast<size_t>(k)] = row[r] * (c == 0 ? right[0] : symmetric ? left[c] + right[c] : left[c] - right[c]);
    }
    return values;
}

double dot(const std::vector<double>& coefficients, const std::array<double, kShapeFields>& values)
{
    const size_t n = std::min(coefficients.size(), values.size());
    double sum = 0;
    for (size_t k = 0; k < n; ++k)
        sum += coefficients[k] * values[k];
    return sum;
}

} // namespace

std::array<double, 2> shapeFieldSums(const std::vector<double>& a, const std::vector<double>& b, double theta, double phi)
{
    return { dot(a, shapeFieldValues(theta, phi, kFieldWidth)), dot(b, shapeFieldValues(theta, phi, kMeanFieldWidth)) };
}

} // namespace facesketch::dataset

#pragma once
// Conformation parameters of one synthetic adult face and their population model.
//
// Linear proportions follow published adult anthropometric norms:
//   Farkas LG. Anthropometry of the Head and Face, 2nd ed. Raven Press, New York, 1994
//   (North American Caucasians aged 19-25; means and standard deviations by sex).
// Every linear measure is drawn as  mean(sex) + sd(sex) * (0.45 g + sqrt(1 - 0.45^2) z),
// where g is one "overall size" factor shared by the face and z is the measure's own
// standard normal, so each measure keeps the norm's mean and SD while sizes correlate.
// Age (uniform 20..65 years) thins the lips, lengthens and drops the nose and narrows the
// eye opening; sex shifts means and brow, jaw and chin prominence.
// The means of parameters that no Farkas norm fixes (nose, lips, eyes, brows, face depth,
// cheeks, jaw and chin) were moved towards the ICT-FaceKit mean face by the mean-face distance
// of `facesketch eval realism` (issue 16, docs/realism.md "Calibration" and "Now (3
// December, later)"); the Farkas measures keep the norms even where ICT differs (en-en, al-al).
//
// Shape fields (issue 16): 49 smooth radial fields (shapeField) with normal coefficients, the
// symmetric ones correlated along each row of the lattice (a shared factor per elevation, weight
// 0.5), so faces vary along many more directions than the measures above, with neighbouring
// regions moving together; a face's own variation on wider bumps than the population's mean
// fields (v19). Their SDs were set by the spectrum of `facesketch eval realism`
// against an ICT import, and the symmetric ones' means (28 numbers) by its mean-face distance,
// with the parameter means: statistics of the ICT set, not any ICT vertex.
//
// Face-wide factors (v15): six standard normals per face, drawn from a stream of their own, of
// which every parameter above and every symmetric field takes a share (weight 0.7, about half
// its variance) through a fixed random direction of loadings, so that one region of a face
// tells of the others as in real faces (the nose predicts the rest to 0.47 of the mean face's
// error, ICT-FaceKit's to 0.36, v14's to 0.60; face_params.cpp). Each draw keeps its mean and
// SD.
//
// Randomness: the portable core/random.h generator (BoxMuller::RedrawZero), so identical seeds
// give identical faces on every standard library.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace facesketch::dataset {

/// One adult anthropometric norm: a distance between two landmarks, mean and SD in mm by sex.
struct Norm {
    const char* name; ///< e.g. "ex-ex"
    const char* from; ///< landmark names in the dataset, e.g. "ex_r"
    const char* to;   ///< e.g. "ex_l"
    double meanMale, sdMale, meanFemale, sdFemale;
};

/// The Farkas (1994) norms the generator reproduces and the tests check: ex-ex, en-en, al-al,
/// ch-ch, n-gn, n-sn, sn-sto.
const std::vector<Norm>& farkasNorms();

/// A small radial bump of "fine random detail", in the face chart (see face_generator.h).
struct DetailBump {
    double theta, phi; ///< centre, radians
    double radius;     ///< radians
    double height;     ///< mm, signed
};

/// Conformation of one face; lengths in mm, angles in degrees unless noted.
struct FaceParams {
    bool female = false;
    double age = 30;

    // Farkas-targeted distances.
    double exex = 91, enen = 33, alal = 35, chch = 53, ngn = 121, nsn = 55, snsto = 22;

    // Nose.
    double tipProtrusion = 20; ///< sn to prn, forward
    double tipRise = 4;        ///< prn above sn
    double dorsumHump = 0;     ///< mm of convexity on the dorsum (negative: concave)
    double bridgeWidth = 6;    ///< half width of the dorsum
    double tipWidth = 9;       ///< half width of the lobule
    double alaSize = 7;        ///< radius of an alar lobule
    double nostrilSize = 3.5;  ///< half length of a nostril
    double nasionDepth = 0;    ///< nasion set back (+) from glabella line

    // Lips and mouth.
    double upperVermilion = 8.5; ///< ls-sto
    double lowerVermilion = 9.5; ///< sto-li
    double upperLipFullness = 5; ///< radial bulge
    double lowerLipFullness = 6;
    double lipProtrusion = 2;
    double cupidBow = 1;
    double philtrumDepth = 0.8;
    double cornerHeight = 0; ///< mouth corners above (+) the slit line
    double lipTaper = 2.5;   ///< the lips' volume thins to the corners as (1 - a^2)^(lipTaper / 2), a = -1..1 (v16)

    // Eyes and brows.
    double fissureHeight = 10.5;
    double canthalTilt = 2;
    double eyeSet = 7; ///< eyeball front behind the face envelope
    double browRidge = 3;
    double browHeight = 18; ///< eyebrow above the canthal line

    // Overall shape.
    double faceDepth = 88;    ///< nasion distance in front of the head centre
    double foreheadSlope = 0; ///< degrees backwards
    double headBreadth = 152;
    double cheekboneWidth = 136; ///< zy-zy
    double cheekboneHeight = 4;  ///< radial prominence
    double cheekFullness = 2;
    double paranasalHollow = 4.5; ///< mm the cheek beside the nose and under the orbit lies back
    double nasolabialDepth = 0.6; ///< mm, the nasolabial fold's crease (face_shape.cpp, v17)
    double jawWidth = 102;        ///< go-go
    double jawAngle = 0;          ///< squareness (-1..1 roughly)
    double chinProjection = 0;    ///< pg forward of the sn-vertical
    double chinWidth = 14;
    double chinHeight = 0; ///< extra chin boss height (mm)
    double neckWidth = 110;

    std::vector<DetailBump> detail;

    /// A face's own coefficients (mm) of the generator's smooth shape fields (shapeField below),
    /// one per field, at kFieldWidth: radial offsets of regions of the face beyond what the
    /// anthropometric measures above describe, so the population varies along many independent
    /// directions (issue 16). They are the face's departure from the population, whose mean
    /// shape fields (shapeFieldMeans, at kMeanFieldWidth) every face shares.
    std::vector<double> shapeModes;
};

/// The smooth shape fields of the generator: a 7 x 4 lattice of Gaussian bumps over the face
/// chart (elevation 0.55 .. -0.95 rad in steps of 0.25, azimuth |theta| 0, 0.3, 0.6, 0.9 rad),
/// each bump mirrored to both sides: the first 28 fields are symmetric (left + right), the next
/// 21 antisymmetric (left - right, the off-midline columns). Field k at (theta, phi) in radians
/// (face_generator.h's chart), bumps exp(-d^2 / width^2); each bump peaks at 1 (-1 on the right
/// side of an antisymmetric field).
inline constexpr int kShapeFields = 49;
/// The population's mean fields are bumps 0.2 rad wide: they were fitted at that width to the
/// ICT-FaceKit mean face. A face's own variation uses wider bumps, 0.28 rad (v19): at 0.2 rad
/// and 2.9 mm the lattice's independent bumps read as lumps on cheeks and temples, and the same
/// spectrum needs no such lumps once each face is placed by its landmarks (face_generator.h,
/// docs/realism.md "v19").
inline constexpr double kMeanFieldWidth = 0.2, kFieldWidth = 0.28;
double shapeField(int k, double theta, double phi, double width);
/// { sum_k a[k] * shapeField(k, theta, phi, kFieldWidth), sum_k b[k] * shapeField(k, theta, phi,
/// kMeanFieldWidth) }, each over its first min(#coefficients, 49) fields, by separable factors
/// (28 exponentials instead of 98): what the generator evaluates, a face's own coefficients and
/// the population means.
std::array<double, 2> shapeFieldSums(const std::vector<double>& a, const std::vector<double>& b, double theta, double phi);
/// The population means of the 49 fields' coefficients (mm, at kMeanFieldWidth): non-zero for
/// the 28 symmetric ones (fitted to the ICT-FaceKit mean face with the parameter means, issue
/// 16), 0 for the antisymmetric ones.
const std::vector<double>& shapeFieldMeans();

/// The face of identity `index` in the population of `seed`: identity i's parameters depend
/// only on (seed, i), so datasets of different sizes share their first faces.
FaceParams sampleFaceParams(std::uint64_t seed, int index);

} // namespace facesketch::dataset

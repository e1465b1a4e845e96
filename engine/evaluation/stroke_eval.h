#pragma once
// How well strokes are read (issue 12): every held-out face is sketched with its own simulated
// strokes (sketch/simulate.h) onto the mean face, from each view alone and from all views
// together, with each mapper (sketch/mapper.h) and the tracking model (sketch/tracking.h), and
// the result is compared with the face the strokes trace: mean per-vertex Euclidean error in mm,
// and its ratio to the mean face's error. Strokes are applied in the order drawn; with all views
// together, the views follow one another in the order given (front, profile, 34 by default).
//
// With `extreme` F != 1 the strokes trace mean + F (face - mean) and that caricature is the
// face scored against (it is what the strokes depict; the mean face's error grows with it).

#include "evaluation/interval.h"
#include "gpu/device.h"
#include "sketch/mapper.h"
#include "sketch/refine.h"
#include "sketch/simulate.h"
#include "sketch/tracking.h"
#include "stats/face_model.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace facesketch::evaluation {

/// Everything on the model's topology (vertex v of the model is vertex v of every mesh here).
struct StrokeEvalData {
    const stats::FaceModel* model = nullptr;
    std::vector<std::uint32_t> flags;                 ///< VertexFlag per model vertex
    std::vector<Mesh> candidateFaces;                 ///< the faces whose contours form the cloud
    std::map<std::string, std::vector<int>> contours; ///< labelled contours, model numbering
    std::vector<std::string> testNames;
    std::vector<Mesh> testFaces; ///< held-out faces, sketched and scored
};

/// What the tracking model is given for each read stroke (a diagnosis of where the error comes
/// from: identity, depth, or the reconstruction itself).
enum class StrokeOracle {
    None,         ///< the reading as it is (the product)
    TrueDepth,    ///< the mapped vertices, each at its position adapted to the stroke but with the
                  ///< traced face's depth along the view axis (identity and in-plane error only)
    TruePosition, ///< the mapped vertices at the traced face's positions (identity error only)
    /// Not the reading's vertices but every vertex the stroke traces (SimulatedStroke::vertices),
    /// each as one row across the true contour at its true image: the tracking model knows
    /// which vertices the stroke draws and where their contour runs, nothing along it. The
    /// ceiling of any reader whose rows say where a contour runs (with --noise 0).
    TrueCurve,
    /// The same vertices at their true image, across and along the contour.
    TrueImage,
};
// An oracle keeps each row's direction: a row across a jittered stroke then measures the true
// position in a slightly wrong direction and passes on some of the truth along the stroke
// (docs/sketching.md, "The across-stroke oracle leaks"). For the ceiling of rows across the
// stroke, run it with --noise 0.

/// "none", "true-depth", "true-position", "true-curve", "true-image"; parseStrokeOracle throws Error naming other text.
const char* strokeOracleName(StrokeOracle oracle);
StrokeOracle parseStrokeOracle(const std::string& text);

struct StrokeEvalOptions {
    std::vector<std::pair<std::string, ViewAngles>> views = { { "front", { 0, 0 } }, { "profile", { 90, 0 } }, { "34", { 45, 0 } } };
    bool allViews = true; ///< also every view's strokes together (view "all")
    std::vector<sketch::MapperKind> mappers
        = { sketch::MapperKind::Nearest, sketch::MapperKind::Heuristic, sketch::MapperKind::Hmm, sketch::MapperKind::Simple };
    sketch::MapperParams params;
    sketch::SimulateOptions simulate; ///< angles ignored (from `views`); seed + face index per face
    sketch::TrackingOptions tracking;
    bool correlation = true;
    /// How each stroke's reading is refined against the face it rebuilt (sketch/refine.h); the
    /// product's default. Statistics of a reading (plane, depth, across, misread) are of the
    /// last reading applied.
    sketch::RefineOptions refine;
    /// Diagnosis only: replace parts of each reading by the truth (StrokeOracle).
    StrokeOracle oracle = StrokeOracle::None;
    /// Keep per-vertex errors and reconstructions of the first this many test faces (renders).
    int keepFaces = 0;
    /// Keep one StrokeEvalStroke per stroke drawn (StrokeEvalResult::strokes): which features a
    /// mapper misreads, repeatably.
    bool keepStrokes = false;
    /// Called after each (face, view) with a line of progress; may be empty.
    std::function<void(const std::string&)> progress;
};

/// One mapper against another on the same faces and strokes.
struct PairedDifference {
    std::string baseline; ///< the other mapper
    /// This record's ratio minus the baseline's in the same view (negative: this mapper rebuilds
    /// better), and its 95% interval with the faces resampled in pairs
    /// (evaluation::bootstrapRatioDifference): "better" is a finding only when the whole
    /// interval lies under 0.
    double difference = 0;
    Interval interval;
    int betterFaces = 0; ///< faces this mapper rebuilt with a lower mean error than the baseline
};

/// One (view, mapper) over every test face.
struct StrokeEvalRecord {
    std::string view, mapper;
    double noisePx = 0, extreme = 1;
    int faces = 0;
    double meanMm = 0;     ///< mean over faces of the mean per-vertex error
    double meanFaceMm = 0; ///< the same for the mean face
    double ratio = 0;      ///< meanMm / meanFaceMm
    /// Its 95% interval over the draw of the faces (evaluation/interval.h): the faces are few,
    /// and a bar counts as met only when the whole interval is under it.
    Interval ratioInterval;
    int strokes = 0;                ///< strokes drawn, over all faces
    int unread = 0;                 ///< strokes the reader pinned nothing with (or refused, counted in failed)
    int failed = 0;                 ///< strokes the reader threw on
    double observedVertices = 0;    ///< mean per face at the end
    double readMs = 0, applyMs = 0; ///< mean per stroke
    /// Of every observation of every read stroke, against the traced face's vertex it names:
    /// the mean distance in the stroke's view plane (mm; how far the stroke point lies from that
    /// vertex's image: the identity error), and the mean absolute depth error along the view
    /// axis (mm) of the observed position. Before any oracle replaces them.
    double planeMm = 0, depthMm = 0;
    /// Of the observations pinned across the stroke (VertexObservation::acrossStroke): the mean
    /// distance of the traced vertex from the stroke point across the stroke (mm), the part of
    /// the identity error the observation passes on to the face.
    double acrossMm = 0;
    /// Fraction of observations whose vertex's traced image lies within 1 mm / 3 mm of the
    /// stroke point in the view plane.
    double within1Mm = 0, within3Mm = 0;
    /// Of the read strokes with observations pinned across the stroke: the fraction whose
    /// median across-stroke error exceeds kMisreadMm, i.e. strokes read as a whole onto another
    /// line (a lower lip onto the upper). Few, but each costs the face far more than the
    /// scattered errors of a good reading (docs/sketching.md, "How far the front view can go").
    double misread = 0;
    /// Against the nearest mapper, when it was run too and this record is another mapper's
    /// (issue 12's bar: the HMM beats nearest in every view). Its ratio's own interval is wide
    /// with 20 faces; paired on the same faces, a difference of a few hundredths can be certain.
    std::optional<PairedDifference> versusNearest;
};

/// The median across-stroke error (mm) above which StrokeEvalRecord::misread counts a stroke.
inline constexpr double kMisreadMm = 1.5;

/// A kept face's result (StrokeEvalOptions::keepFaces).
struct StrokeEvalFace {
    std::string face, view, mapper;
    double meanMm = 0;
    Eigen::VectorXd vertexError; ///< #V, mm
    Mesh reconstruction;
};

/// One stroke's reading against the face it traces (StrokeEvalOptions::keepStrokes), measured
/// as StrokeEvalRecord measures all of a view's: of the last reading applied, before any oracle.
struct StrokeEvalStroke {
    enum class Outcome { Read, Unread, Failed };
    std::string face, view, mapper;
    std::string feature; ///< the traced contour's name, or "silhouette"
    /// The labelled contour most of its observed vertices lie on (StrokeEvalData::contours), or
    /// "unlabelled" when most lie on none (silhouettes, suggestive contours); empty unless read.
    std::string readAs;
    int index = 0;  ///< its place among the view's strokes (view "all": every view's in turn)
    int points = 0; ///< points drawn
    Outcome outcome = Outcome::Read;
    int observations = 0;
    double planeMm = 0, depthMm = 0; ///< means over its observations (0 without any)
    /// The median across-stroke error of its observations pinned across the stroke (mm), and
    /// whether it exceeds kMisreadMm; nullopt without such observations.
    std::optional<double> acrossMm;
    bool misread = false;
    double readMs = 0;
};

const char* strokeOutcomeName(StrokeEvalStroke::Outcome outcome);

/// Per (view, feature, mapper), of kept strokes: how many were drawn, read (pinned something)
/// and misread (StrokeEvalStroke::misread), and the mean of the read strokes' median
/// across-stroke errors. Rows in the order each view, feature and mapper first appears.
struct FeatureReadings {
    std::string view, feature, mapper;
    int strokes = 0, read = 0, misread = 0;
    double acrossMm = 0;                  ///< mean over the read strokes with an across-stroke error
    std::map<std::string, int> misreadAs; ///< the misread strokes by StrokeEvalStroke::readAs
};
std::vector<FeatureReadings> readingsByFeature(const std::vector<StrokeEvalStroke>& strokes);

struct StrokeEvalResult {
    std::vector<StrokeEvalRecord> records; ///< per view (then "all"), per mapper in the order given
    std::vector<StrokeEvalFace> kept;
    std::vector<StrokeEvalStroke> strokes; ///< every stroke, when StrokeEvalOptions::keepStrokes
    std::vector<std::string> notes;        ///< e.g. the first message of each failed stroke
};

/// Runs the measurement (GPU candidate clouds through sketch::StrokeReader). Throws Error for
/// data of another topology than the model's, no test faces or no mappers.
StrokeEvalResult evaluateStrokes(gpu::Device& device, const StrokeEvalData& data, const StrokeEvalOptions& options);

} // namespace facesketch::evaluation

#include "evaluation/stroke_eval.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "sketch/refine.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

namespace facesketch::evaluation {

namespace {

Mesh meshOf(const Eigen::VectorXd& flat, const Triangles& F)
{
    Mesh m;
    m.F = F;
    m.V = asVertices(flat);
    return m;
}

Eigen::VectorXd vertexErrors(const Eigen::VectorXd& face, const Mesh& truth)
{
    Eigen::VectorXd e(truth.V.rows());
    for (Eigen::Index v = 0; v < truth.V.rows(); ++v)
        e[v] = (face.segment<3>(3 * v) - truth.V.row(v).transpose()).norm();
    return e;
}

Eigen::Vector3d axisOf(const Eigen::Matrix<double, 2, 3>& P)
{
    return P.row(0).transpose().cross(P.row(1).transpose()).normalized();
}

// One reading's observations against the traced face, before any oracle changes them.
struct ReadingErrors {
    double planeMm = 0, depthMm = 0, within1 = 0, within3 = 0, acrossMm = 0;
    long observations = 0, across = 0;
    bool hasAcross = false, misread = false;
    double medianAcrossMm = 0; ///< when hasAcross
};

ReadingErrors readingErrors(const sketch::StrokeReading& reading, const Mesh& traced)
{
    ReadingErrors r;
    const Eigen::Matrix<double, 2, 3>& P = reading.viewPlane;
    const Eigen::Vector3d axis = axisOf(P);
    std::vector<double> acrossErrors;
    for (const sketch::VertexObservation& o : reading.observations) {
        const Eigen::Vector3d truth = traced.V.row(o.vertex).transpose();
        const double plane = (P * (o.position - truth)).norm();
        r.planeMm += plane;
        r.depthMm += std::abs(axis.dot(o.position - truth));
        r.within1 += plane <= 1.0;
        r.within3 += plane <= 3.0;
        ++r.observations;
        if (!o.acrossStroke.isZero()) {
            acrossErrors.push_back(std::abs(o.acrossStroke.dot(o.position - truth)));
            r.acrossMm += acrossErrors.back();
            ++r.across;
        }
    }
    if (!acrossErrors.empty()) {
        const auto middle = acrossErrors.begin() + static_cast<std::ptrdiff_t>(acrossErrors.size() / 2);
        std::nth_element(acrossErrors.begin(), middle, acrossErrors.end());
        r.hasAcross = true;
        r.medianAcrossMm = *middle;
        r.misread = *middle > kMisreadMm;
    }
    return r;
}

// The labelled contour most of a reading's vertices lie on (each vertex counted once per
// contour it lies on), or "unlabelled" when more vertices lie on none than on any one contour.
std::string dominantContour(const sketch::StrokeReading& reading, const std::vector<std::vector<std::string>>& contoursOf)
{
    std::map<std::string, int> votes;
    for (const sketch::VertexObservation& o : reading.observations) {
        const std::vector<std::string>& names = contoursOf[o.vertex];
        if (names.empty())
            ++votes["unlabelled"];
        for (const std::string& name : names)
            ++votes[name];
    }
    std::string best;
    int most = 0;
    for (const auto& [name, count] : votes)
        if (count > most) {
            best = name;
            most = count;
        }
    return best;
}

struct Sums {
    double mean = 0, meanFace = 0, observed = 0, readMs = 0, applyMs = 0;
    int faces = 0, strokes = 0, unread = 0, failed = 0;
    double planeMm = 0, depthMm = 0, within1 = 0, within3 = 0, acrossMm = 0;
    long observations = 0, across = 0;
    int acrossStrokes = 0, misread = 0;
    std::vector<double> faceMeans, meanFaceMeans; ///< per face, for the ratio's interval

    void add(const ReadingErrors& r)
    {
        planeMm += r.planeMm;
        depthMm += r.depthMm;
        within1 += r.within1;
        within3 += r.within3;
        acrossMm += r.acrossMm;
        observations += r.observations;
        across += r.across;
        acrossStrokes += r.hasAcross;
        misread += r.misread;
    }
};

// The vertices a simulated stroke traces at their true positions, measured in the view plane P:
// across their contour only (the normal of the contour's image through each vertex's
// neighbours on it), or their whole image.
std::vector<sketch::VertexObservation> tracedContour(
    const sketch::SimulatedStroke& stroke, const Mesh& traced, const Eigen::Matrix<double, 2, 3>& P, bool acrossOnly)
{
    std::vector<sketch::VertexObservation> out;
    const std::vector<int>& v = stroke.vertices;
    std::set<int> seen;
    for (size_t i = 0; i < v.size(); ++i) {
        if (!seen.insert(v[i]).second)
            continue;
        sketch::VertexObservation o;
        o.vertex = static_cast<std::uint32_t>(v[i]);
        o.position = traced.V.row(v[i]).transpose();
        o.viewPlaneOnly = true;
        if (acrossOnly) {
            const int before = v[i > 0 ? i - 1 : i], after = v[i + 1 < v.size() ? i + 1 : i];
            const Eigen::Vector2d t = P * (traced.V.row(after) - traced.V.row(before)).transpose();
            if (t.norm() < 1e-9)
                continue;
            o.acrossStroke = P.transpose() * Eigen::Vector2d(-t.y(), t.x()).normalized();
        }
        out.push_back(o);
    }
    return out;
}

} // namespace

const char* strokeOutcomeName(StrokeEvalStroke::Outcome outcome)
{
    switch (outcome) {
    case StrokeEvalStroke::Outcome::Read:
        return "read";
    case StrokeEvalStroke::Outcome::Unread:
        return "unread";
    case StrokeEvalStroke::Outcome::Failed:
        return "failed";
    }
    return "unknown";
}

std::vector<FeatureReadings> readingsByFeature(const std::vector<StrokeEvalStroke>& strokes)
{
    // First-appearance ranks, so that rows follow the evaluation's own order.
    std::map<std::string, int> views, features, mappers;
    const auto rank = [](std::map<std::string, int>& order, const std::string& name) {
        return order.try_emplace(name, static_cast<int>(order.size())).first->second;
    };
    std::map<std::tuple<int, int, int>, FeatureReadings> rows;
    std::map<std::tuple<int, int, int>, int> acrossCounts;
    for (const StrokeEvalStroke& s : strokes) {
        const auto key = std::make_tuple(rank(views, s.view), rank(features, s.feature), rank(mappers, s.mapper));
        FeatureReadings& row = rows[key];
        row.view = s.view;
        row.feature = s.feature;
        row.mapper = s.mapper;
        ++row.strokes;
        if (s.outcome != StrokeEvalStroke::Outcome::Read)
            continue;
        ++row.read;
        row.misread += s.misread;
        if (s.misread)
            ++row.misreadAs[s.readAs];
        if (s.acrossMm) {
            row.acrossMm += *s.acrossMm;
            ++acrossCounts[key];
        }
    }
    std::vector<FeatureReadings> out;
    for (auto& [key, row] : rows) {
        if (const int n = acrossCounts[key]; n > 0)
            row.acrossMm /= n;
        out.push_back(row);
    }
    return out;
}

const char* strokeOracleName(StrokeOracle oracle)
{
    switch (oracle) {
    case StrokeOracle::None:
        return "none";
    case StrokeOracle::TrueDepth:
        return "true-depth";
    case StrokeOracle::TruePosition:
        return "true-position";
    case StrokeOracle::TrueCurve:
        return "true-curve";
    case StrokeOracle::TrueImage:
        return "true-image";
    }
    return "unknown";
}

StrokeOracle parseStrokeOracle(const std::string& text)
{
    for (StrokeOracle o :
        { StrokeOracle::None, StrokeOracle::TrueDepth, StrokeOracle::TruePosition, StrokeOracle::TrueCurve, StrokeOracle::TrueImage })
        if (text == strokeOracleName(o))
            return o;
    fail("oracle '", text, "' is none of none, true-depth, true-position, true-curve, true-image");
}

StrokeEvalResult evaluateStrokes(gpu::Device& device, const StrokeEvalData& data, const StrokeEvalOptions& options)
{
    if (!data.model)
        fail("evaluateStrokes: no model");
    const stats::FaceModel& model = *data.model;
    const Eigen::Index nv = model.vertexCount();
    if (data.testFaces.empty() || data.testNames.size() != data.testFaces.size())
        fail("evaluateStrokes: need named test faces");
    if (options.mappers.empty() || options.views.empty())
        fail("evaluateStrokes: need at least one view and one mapper");
    for (size_t i = 0; i < data.testFaces.size(); ++i)
        if (data.testFaces[i].V.rows() != nv || data.testFaces[i].F != model.triangles)
            fail("evaluateStrokes: test face ", data.testNames[i], " is not on the model's topology (", data.testFaces[i].V.rows(),
                " vertices, the model ", nv, ")");

    const Mesh mean = meshOf(model.meanFace, model.triangles);
    std::vector<std::vector<std::string>> contoursOf(static_cast<size_t>(nv));
    if (options.keepStrokes)
        for (const auto& [name, path] : data.contours) {
            std::set<int> once(path.begin(), path.end()); // a closed loop repeats its first vertex
            for (int v : once)
                if (v >= 0 && v < nv)
                    contoursOf[static_cast<size_t>(v)].push_back(name);
        }
    sketch::StrokeReader reader(device, model, data.candidateFaces, data.flags);

    // Per view name (then "all"), per mapper.
    std::vector<std::string> viewNames;
    for (const auto& [name, angles] : options.views)
        viewNames.push_back(name);
    if (options.allViews && options.views.size() > 1)
        viewNames.push_back("all");
    std::map<std::pair<std::string, int>, Sums> sums;
    StrokeEvalResult result;

    for (size_t f = 0; f < data.testFaces.size(); ++f) {
        // The strokes of every view, simulated once per face and shared by the mappers.
        std::vector<std::vector<sketch::SimulatedStroke>> strokes;
        Mesh traced;
        for (const auto& [name, angles] : options.views) {
            sketch::SimulateOptions so = options.simulate;
            so.angles = angles;
            so.seed = options.simulate.seed + 7919 * f;
            sketch::Simulation sim = sketch::simulateStrokes(data.testFaces[f], mean, data.contours, data.flags, so);
            strokes.push_back(std::move(sim.strokes));
            traced = std::move(sim.traced);
        }
        const double meanFaceError = vertexErrors(model.meanFace, traced).mean();

        for (const std::string& view : viewNames) {
            std::vector<const sketch::SimulatedStroke*> sequence;
            for (size_t k = 0; k < options.views.size(); ++k)
                if (view == "all" || view == options.views[k].first)
                    for (const auto& s : strokes[k])
                        sequence.push_back(&s);
            for (size_t m = 0; m < options.mappers.size(); ++m) {
                const sketch::MapperKind kind = options.mappers[m];
                sketch::TrackingModel tracking(model, options.tracking);
                Sums& s = sums[{ view, static_cast<int>(m) }];
                sketch::ApplyOptions apply;
                apply.correlation = options.correlation;
                for (size_t k = 0; k < sequence.size(); ++k) {
                    const sketch::SimulatedStroke* stroke = sequence[k];
                    ++s.strokes;
                    StrokeEvalStroke record;
                    if (options.keepStrokes) {
                        record.face = data.testNames[f];
                        record.view = view;
                        record.mapper = sketch::mapperName(kind);
                        record.feature = stroke->feature;
                        record.index = static_cast<int>(k);
                        record.points = static_cast<int>(stroke->stroke.points.size());
                    }
                    const auto keep = [&](StrokeEvalStroke::Outcome outcome, const ReadingErrors* errors, double readMs) {
                        if (!options.keepStrokes)
                            return;
                        record.outcome = outcome;
                        record.readMs = readMs;
                        // A pass that ran before the reader threw (or read nothing) set readAs;
                        // the stroke itself was not read as anything.
                        if (outcome != StrokeEvalStroke::Outcome::Read)
                            record.readAs.clear();
                        if (errors && errors->observations > 0) {
                            record.observations = static_cast<int>(errors->observations);
                            record.planeMm = errors->planeMm / static_cast<double>(errors->observations);
                            record.depthMm = errors->depthMm / static_cast<double>(errors->observations);
                        }
                        if (errors && errors->hasAcross) {
                            record.acrossMm = errors->medianAcrossMm;
                            record.misread = errors->misread;
                        }
                        result.strokes.push_back(std::move(record));
                    };
                    // What the last reading applied measured against the truth (each pass's
                    // reading replaces the previous one's, so the last one is counted).
                    ReadingErrors last;
                    const sketch::ReadingHook hook = [&](sketch::StrokeReading& reading) {
                        last = readingErrors(reading, traced);
                        if (options.keepStrokes)
                            record.readAs = dominantContour(reading, contoursOf);
                        if (options.oracle == StrokeOracle::TrueCurve || options.oracle == StrokeOracle::TrueImage)
                            reading.observations
                                = tracedContour(*stroke, traced, reading.viewPlane, options.oracle == StrokeOracle::TrueCurve);
                        else if (options.oracle != StrokeOracle::None) {
                            const Eigen::Vector3d axis = axisOf(reading.viewPlane);
                            for (sketch::VertexObservation& o : reading.observations) {
                                const Eigen::Vector3d truth = traced.V.row(o.vertex).transpose();
                                if (options.oracle == StrokeOracle::TrueDepth)
                                    o.position += axis * axis.dot(truth - o.position);
                                else
                                    o.position = truth;
                            }
                        }
                    };
                    sketch::ReadResult done;
                    try {
                        done = sketch::readAndApply(reader, tracking, stroke->stroke, kind, options.params, apply, options.refine, hook);
                    } catch (const Error& e) {
                        // A simulated stroke the reader refuses is a finding, not a reason to
                        // stop: counted and its first message kept.
                        if (s.failed++ == 0)
                            result.notes.push_back(
                                cat(view, " ", sketch::mapperName(kind), " ", data.testNames[f], " ", stroke->feature, ": ", e.what()));
                        keep(StrokeEvalStroke::Outcome::Failed, nullptr, 0);
                        continue;
                    }
                    s.readMs += done.readMs;
                    if (done.reading.observations.empty()) {
                        ++s.unread;
                        keep(StrokeEvalStroke::Outcome::Unread, nullptr, done.readMs);
                        continue;
                    }
                    s.applyMs += done.applyMs;
                    s.add(last);
                    keep(StrokeEvalStroke::Outcome::Read, &last, done.readMs);
                }
                const Eigen::VectorXd e = vertexErrors(tracking.face(), traced);
                s.mean += e.mean();
                s.meanFace += meanFaceError;
                s.faceMeans.push_back(e.mean());
                s.meanFaceMeans.push_back(meanFaceError);
                s.observed += tracking.observedVertices();
                ++s.faces;
                if (static_cast<int>(f) < options.keepFaces)
                    result.kept.push_back({ data.testNames[f], view, sketch::mapperName(kind), e.mean(), e, tracking.faceMesh() });
            }
            if (options.progress) {
                std::string line = cat(data.testNames[f], " ", view, ":");
                for (size_t m = 0; m < options.mappers.size(); ++m) {
                    const Sums& s = sums[{ view, static_cast<int>(m) }];
                    line += cat(" ", sketch::mapperName(options.mappers[m]), " ", s.mean / s.faces, " mm");
                }
                options.progress(cat(line, " (mean face ", meanFaceError, " mm, ", sequence.size(), " strokes)"));
            }
        }
    }

    const auto nearest = std::find(options.mappers.begin(), options.mappers.end(), sketch::MapperKind::Nearest);
    for (const std::string& view : viewNames)
        for (size_t m = 0; m < options.mappers.size(); ++m) {
            const Sums& s = sums[{ view, static_cast<int>(m) }];
            StrokeEvalRecord r;
            r.view = view;
            r.mapper = sketch::mapperName(options.mappers[m]);
            r.noisePx = options.simulate.noisePx;
            r.extreme = options.simulate.extreme;
            r.faces = s.faces;
            r.meanMm = s.mean / s.faces;
            r.meanFaceMm = s.meanFace / s.faces;
            r.ratio = r.meanMm / r.meanFaceMm;
            if (s.faces > 0)
                r.ratioInterval = bootstrapRatio(s.faceMeans, s.meanFaceMeans);
            r.strokes = s.strokes;
            r.unread = s.unread;
            r.failed = s.failed;
            r.observedVertices = s.observed / s.faces;
            const int read = s.strokes - s.failed;
            r.readMs = read > 0 ? s.readMs / read : 0;
            r.applyMs = read - s.unread > 0 ? s.applyMs / (read - s.unread) : 0;
            if (s.observations > 0) {
                const double n = static_cast<double>(s.observations);
                r.planeMm = s.planeMm / n;
                r.depthMm = s.depthMm / n;
                r.within1Mm = s.within1 / n;
                r.within3Mm = s.within3 / n;
            }
            if (s.across > 0)
                r.acrossMm = s.acrossMm / static_cast<double>(s.across);
            if (s.acrossStrokes > 0)
                r.misread = static_cast<double>(s.misread) / s.acrossStrokes;
            if (nearest != options.mappers.end() && options.mappers[m] != sketch::MapperKind::Nearest && s.faces > 0) {
                // The same faces in the same order: the per-face errors pair up.
                const Sums& b = sums[{ view, static_cast<int>(nearest - options.mappers.begin()) }];
                PairedDifference p;
                p.baseline = sketch::mapperName(sketch::MapperKind::Nearest);
                p.difference = (s.mean - b.mean) / s.meanFace;
                p.interval = bootstrapRatioDifference(s.faceMeans, b.faceMeans, s.meanFaceMeans);
                for (size_t f = 0; f < s.faceMeans.size(); ++f)
                    p.betterFaces += s.faceMeans[f] < b.faceMeans[f];
                r.versusNearest = p;
            }
            result.records.push_back(r);
        }
    return result;
}

} // namespace facesketch::evaluation

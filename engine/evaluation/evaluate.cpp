#include "evaluation/evaluate.h"

#include "core/error.h"
#include "core/random.h"
#include "core/stopwatch.h"
#include "stats/check.h"

#include <algorithm>

namespace facesketch::evaluation {

using namespace facesketch::stats;

ObserveScore evaluateObserve(const FaceModel& model, const Eigen::MatrixXd& faces, const ObserveOptions& options)
{
    requireFinite(faces, "evaluateObserve: faces");
    const Eigen::Index vertices = model.vertexCount();
    if (faces.cols() != 3 * vertices)
        fail("evaluateObserve: faces have ", faces.cols(), " columns, the model has ", 3 * vertices);
    if (options.region.empty() && !(options.fraction > 0.0 && options.fraction <= 1.0))
        fail("evaluateObserve: fraction ", options.fraction, " outside (0, 1]");
    for (int v : options.region)
        if (v < 0 || v >= vertices)
            fail("evaluateObserve: region vertex ", v, " outside [0, ", vertices, ")");

    Random random(options.seed);
    ObserveScore score;
    double reconstructionMs = 0.0;
    Eigen::Index measured = 0;
    std::vector<double> faceErrors, meanFaceErrors;
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
        const Eigen::VectorXd truth = faces.row(f).transpose();
        Observations obs;
        if (options.region.empty()) {
            for (Eigen::Index v = 0; v < vertices; ++v)
                if (random.uniform() < options.fraction)
                    obs.addVertex(v, truth.segment<3>(3 * v));
        } else {
            for (int v : options.region)
                obs.addVertex(v, truth.segment<3>(3 * v));
        }
        measured += obs.size() / 3;
        Stopwatch watch;
        const Eigen::VectorXd face = reconstruct(model, obs, options.reconstruct).face;
        reconstructionMs += watch.milliseconds();
        double faceError = 0, meanFaceError = 0;
        for (Eigen::Index v = 0; v < vertices; ++v) {
            const double e = (face.segment<3>(3 * v) - truth.segment<3>(3 * v)).norm();
            const double m = (model.meanFace.segment<3>(3 * v) - truth.segment<3>(3 * v)).norm();
            faceError += e;
            meanFaceError += m;
            score.maxError = std::max(score.maxError, e);
            score.meanFaceMaxError = std::max(score.meanFaceMaxError, m);
        }
        score.meanError += faceError;
        score.meanFaceMeanError += meanFaceError;
        faceErrors.push_back(faceError);
        meanFaceErrors.push_back(meanFaceError);
    }
    score.faces = static_cast<int>(faces.rows());
    if (score.faces > 0) {
        const double count = static_cast<double>(faces.rows() * vertices);
        score.meanError /= count;
        score.meanFaceMeanError /= count;
        score.measuredFraction = static_cast<double>(measured) / count;
        score.millisecondsPerFace = reconstructionMs / score.faces;
        if (score.meanFaceMeanError > 0)
            score.ratioInterval = bootstrapRatio(faceErrors, meanFaceErrors);
    }
    return score;
}

} // namespace facesketch::evaluation

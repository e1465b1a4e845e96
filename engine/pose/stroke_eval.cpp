#include "pose/stroke_eval.h"

#include "core/error.h"
#include "core/random.h"

#include <cmath>

namespace facesketch::pose {

std::vector<sketch::Stroke> simulatePoseStrokes(
    const Mesh& posed, const Mesh& neutral, const std::map<std::string, std::vector<int>>& contours, const PoseStrokeSimulation& options)
{
    if (std::isnan(options.noisePx) || options.noisePx < 0)
        fail("pose strokes: noise ", options.noisePx, " px is not >= 0");
    const OrbitView view = frameMeshView(neutral, parseView("front"), options.imageSize, options.imageSize);
    const Camera camera = orbitCamera(view);
    Random random(options.seed);
    std::vector<sketch::Stroke> strokes;
    for (const std::string& name : options.contours) {
        const auto it = contours.find(name);
        if (it == contours.end())
            fail("pose strokes: the dataset labels no contour ", name);
        sketch::Stroke stroke;
        stroke.view = view;
        for (int v : it->second) {
            if (v < 0 || v >= posed.vertexCount())
                fail("pose strokes: contour ", name, " vertex ", v, " outside the face's ", posed.vertexCount());
            const glm::dvec3 p = camera.project({ posed.V(v, 0), posed.V(v, 1), posed.V(v, 2) });
            const double dx = options.noisePx * random.normal();
            const double dy = options.noisePx * random.normal();
            stroke.points.push_back({ p.x + dx, p.y + dy, {} });
        }
        strokes.push_back(std::move(stroke));
    }
    return strokes;
}

StrokePoseEvaluation evaluateStrokePoses(const PoseModel& model, const PoseSet& test,
    const std::map<std::string, std::vector<int>>& contours, const PoseStrokeSimulation& simulation, const PoseStrokeOptions& options)
{
    if (test.identityCount() == 0)
        fail("eval poses (strokes): no test identities");
    if (test.vertexCount != model.vertexCount || test.fps.names != model.fps.names)
        fail("eval poses (strokes): the test poses have another topology or other FPs than the pose model");
    StrokePoseEvaluation result;
    double sum = 0, neutralSum = 0;
    int pairs = 0;
    for (Eigen::Index p = 0; p < test.poseCount(); ++p) {
        const std::string& name = test.poseNames[static_cast<std::size_t>(p)];
        if (name == "neutral")
            continue;
        evaluation::PosePoseError perPose { name, "strokes", "statistical", 0.0, 0.0 };
        for (Eigen::Index i = 0; i < test.identityCount(); ++i) {
            Mesh neutral { asVertices(Eigen::VectorXd(test.neutrals.row(i).transpose())), test.topology };
            Mesh posed = neutral;
            asVector(posed.V) += test.meshDisplacements.row(test.row(i, p)).transpose();
            PoseStrokeSimulation s = simulation;
            s.seed = simulation.seed + static_cast<std::uint64_t>(i * test.poseCount() + p);
            PoseEditor editor(model, neutral, options);
            for (const sketch::Stroke& stroke : simulatePoseStrokes(posed, neutral, contours, s)) {
                sketch::PoseAction action;
                action.stroke = stroke;
                ++result.strokes;
                try {
                    editor.apply(action);
                } catch (const Error&) {
                    ++result.refused;
                }
            }
            const double error = (editor.face().V - posed.V).rowwise().norm().mean();
            const double baseline = (neutral.V - posed.V).rowwise().norm().mean();
            perPose.meanMm += error / static_cast<double>(test.identityCount());
            perPose.neutralMm += baseline / static_cast<double>(test.identityCount());
            sum += error;
            neutralSum += baseline;
            ++pairs;
        }
        result.perPose.push_back(perPose);
    }
    result.record.task = "strokes";
    result.record.method = "statistical";
    result.record.poses = static_cast<int>(result.perPose.size());
    result.record.meanMm = pairs > 0 ? sum / pairs : 0.0;
    result.record.ratio = neutralSum > 0 ? sum / neutralSum : 0.0;
    return result;
}

} // namespace facesketch::pose

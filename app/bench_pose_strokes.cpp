#include "bench_pose_strokes.h"

#include "bench.h"
#include "core/stopwatch.h"
#include "pose/pose_session.h"
#include "pose/stroke_eval.h"

namespace facesketch::app {

void benchPoseStrokes(const pose::PoseModel& model, const Mesh& neutral, const Mesh& posed,
    const std::map<std::string, std::vector<int>>& contours, int repeat, std::ostream& out)
{
    const std::vector<sketch::Stroke> strokes = pose::simulatePoseStrokes(posed, neutral, contours);
    std::vector<double> perStroke;
    std::size_t points = 0;
    for (const auto& s : strokes)
        points += s.points.size();
    for (int r = 0; r < std::max(repeat, 1); ++r) {
        pose::PoseEditor editor(model, neutral);
        for (const sketch::Stroke& stroke : strokes) {
            sketch::PoseAction action;
            action.stroke = stroke;
            Stopwatch clock;
            editor.apply(action);
            perStroke.push_back(clock.milliseconds());
        }
    }
    out << "# pose strokes: " << strokes.size() << " strokes (" << points << " points, lips and brows from the front), "
        << std::max(repeat, 1) << " repetitions, " << neutral.vertexCount() << " vertices\n";
    out << "pose_stroke_ms_" << neutral.vertexCount() << "v " << median(perStroke) << " ms\n";
}

} // namespace facesketch::app

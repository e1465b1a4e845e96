#include "pose/pose_session.h"

#include "core/error.h"
#include "sketch/projection.h"
#include "sketch/stroke_candidates.h"

#include <algorithm>
#include <cmath>

namespace facesketch::pose {

PoseEditor::PoseEditor(const PoseModel& model, const Mesh& neutral, const PoseStrokeOptions& options)
    : model_(model)
    , neutral_(neutral)
    , options_(options)
{
    checkFace(model, neutral, "the face to pose");
    if (!std::isfinite(options.readingNoiseMm) || options.readingNoiseMm < 0)
        fail("pose strokes: reading noise ", options.readingNoiseMm, " mm is not a finite value >= 0");
    clusters_ = fpClusters(model.fps, model.fpTraining, neutral.V, options.clusters);
    State start;
    start.pose = Eigen::VectorXd::Zero(3 * model.fpCount());
    start.face = neutral;
    states_.push_back(std::move(start));
}

void PoseEditor::apply(const sketch::PoseAction& action)
{
    // Everything is computed into `next`; the history changes only once nothing can throw.
    State next = states_[current_];
    switch (action.kind) {
    case sketch::PoseActionKind::Stroke: {
        sketch::validateStroke(action.stroke, "pose stroke");
        const Camera camera = orbitCamera(action.stroke.view);
        const sketch::ProjectedStroke projected
            = sketch::projectStroke(action.stroke, camera, states_[current_].face, options_.maxGapPx, options_.tension);
        next.strokes.push_back({ projected.world, sketch::viewPlaneRows(camera) });
        next.reading = identifyFps(clusters_, next.strokes, options_.reading);
        const Completion completion = completePose(model_, poseObservations(model_.fps, neutral_.V, next.reading),
            action.alternative ? Interpretation::Alternative : Interpretation::Primary, options_.readingNoiseMm);
        next.pose = completion.fp;
        next.component = completion.winner;
        next.face.V = posedFace(model_, neutral_.V, next.pose);
        break;
    }
    case sketch::PoseActionKind::Keyframe:
        if (!std::isfinite(action.time) || action.time < 0)
            fail("keyframe: time ", action.time, " is not a time >= 0 in seconds");
        for (const Keyframe& key : next.keyframes)
            if (key.time == action.time)
                fail("keyframe: there is a keyframe at ", action.time, " s already");
        next.keyframes.push_back({ action.time, next.pose });
        break;
    case sketch::PoseActionKind::MoveKeyframe:
    case sketch::PoseActionKind::DeleteKeyframe: {
        const bool move = action.kind == sketch::PoseActionKind::MoveKeyframe;
        const auto key
            = std::find_if(next.keyframes.begin(), next.keyframes.end(), [&](const Keyframe& k) { return k.time == action.time; });
        if (key == next.keyframes.end())
            fail(move ? "keyframe move" : "keyframe delete", ": there is no keyframe at ", action.time, " s");
        if (!move) {
            next.keyframes.erase(key);
            break;
        }
        if (!std::isfinite(action.to) || action.to < 0)
            fail("keyframe move: time ", action.to, " is not a time >= 0 in seconds");
        for (const Keyframe& other : next.keyframes)
            if (other.time == action.to && &other != &*key)
                fail("keyframe move: there is a keyframe at ", action.to, " s already");
        key->time = action.to;
        break;
    }
    case sketch::PoseActionKind::Clear:
        next.strokes.clear();
        next.reading = {};
        next.pose.setZero();
        next.component = -1;
        next.face = neutral_;
        break;
    }
    states_.resize(current_ + 1);
    states_.push_back(std::move(next));
    ++current_;
}

bool PoseEditor::undo()
{
    if (current_ == 0)
        return false;
    --current_;
    return true;
}

bool PoseEditor::redo()
{
    if (current_ + 1 >= states_.size())
        return false;
    ++current_;
    return true;
}

Vertices PoseEditor::featurePointPositions() const
{
    Vertices P(model_.fpCount(), 3);
    for (Eigen::Index i = 0; i < model_.fpCount(); ++i)
        P.row(i) = neutral_.V.row(model_.fps.vertices[static_cast<std::size_t>(i)]) + pose().segment<3>(3 * i).transpose();
    return P;
}

Timeline PoseEditor::timeline(double tension) const
{
    return Timeline(keyframes(), tension);
}

void replayPoseActions(PoseEditor& editor, const sketch::Session& session)
{
    static const char* const names[] = { "pose-stroke", "keyframe", "pose-clear", "keyframe-move", "keyframe-delete" };
    for (std::size_t i = 0; i < session.poseActions.size(); ++i) {
        const sketch::PoseAction& action = session.poseActions[i];
        try {
            editor.apply(action);
        } catch (const Error& e) {
            // The file's one list holds the shape strokes before it too.
            fail("actions[", i + static_cast<std::size_t>(action.afterStrokes), "] (", names[static_cast<int>(action.kind)],
                "): ", e.what());
        }
    }
}

std::vector<double> frameTimes(const Timeline& timeline, double fps)
{
    if (!(fps > 0) || !std::isfinite(fps))
        fail("frames per second: ", fps, " is not > 0");
    const double span = timeline.end() - timeline.begin();
    const double steps = std::ceil(span * fps - 1e-9);
    if (steps + 1 > 100000)
        fail("frames per second: ", fps, " over ", span, " s makes ", steps + 1, " frames, more than 100,000");
    std::vector<double> times;
    const auto n = static_cast<std::size_t>(steps);
    for (std::size_t k = 0; k < n; ++k)
        times.push_back(timeline.begin() + static_cast<double>(k) / fps);
    times.push_back(timeline.end());
    return times;
}

} // namespace facesketch::pose

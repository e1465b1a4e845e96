#include "pose/timeline.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>

namespace facesketch::pose {

Timeline::Timeline(std::vector<Keyframe> keyframes, double tension)
{
    if (!(tension >= 0.0 && tension <= 1.0))
        fail("timeline: tension ", tension, " outside [0, 1]");
    if (keyframes.size() < 2)
        fail("timeline: ", keyframes.size(), " keyframe(s), a timeline needs at least 2");
    const Eigen::Index d = keyframes.front().fp.size();
    for (size_t k = 0; k < keyframes.size(); ++k) {
        const Keyframe& key = keyframes[k];
        if (!std::isfinite(key.time))
            fail("timeline: keyframe ", k, " has time ", key.time);
        if (key.fp.size() == 0 || key.fp.size() != d)
            fail("timeline: keyframe ", k, " has a pose of ", key.fp.size(), " values, keyframe 0 has ", d);
        for (Eigen::Index i = 0; i < d; ++i)
            if (!std::isfinite(key.fp(i)))
                fail("timeline: keyframe ", k, " (time ", key.time, ") value ", i, " = ", key.fp(i), " is not finite");
    }
    std::stable_sort(keyframes.begin(), keyframes.end(), [](const Keyframe& a, const Keyframe& b) { return a.time < b.time; });
    for (size_t k = 1; k < keyframes.size(); ++k)
        if (keyframes[k].time == keyframes[k - 1].time)
            fail("timeline: two keyframes at time ", keyframes[k].time);

    const size_t N = keyframes.size();
    tangents_.resize(N);
    for (size_t k = 0; k < N; ++k) {
        const size_t a = k == 0 ? 0 : k - 1;
        const size_t b = k + 1 == N ? N - 1 : k + 1;
        tangents_[k] = (1.0 - tension) * (keyframes[b].fp - keyframes[a].fp) / (keyframes[b].time - keyframes[a].time);
    }
    keyframes_ = std::move(keyframes);
    tension_ = tension;
}

void Timeline::sample(double t, Eigen::VectorXd& out) const
{
    // isnan first: an ordered comparison with NaN raises the invalid flag (trapped in tests).
    if (std::isnan(t) || t < begin() || t > end())
        fail("timeline: time ", t, " outside the timeline [", begin(), ", ", end(), "]");
    // The segment [t_k, t_k+1] holding t; t = end() falls in the last one.
    const auto it = std::upper_bound(keyframes_.begin(), keyframes_.end(), t, [](double x, const Keyframe& key) { return x < key.time; });
    const size_t k = std::min(static_cast<size_t>(it - keyframes_.begin()), keyframes_.size() - 1) - 1;
    const Keyframe& a = keyframes_[k];
    const Keyframe& b = keyframes_[k + 1];
    const double h = b.time - a.time;
    const double s = (t - a.time) / h;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    out.resize(dim());
    out.noalias() = h00 * a.fp + (h10 * h) * tangents_[k] + h01 * b.fp + (h11 * h) * tangents_[k + 1];
}

Eigen::VectorXd Timeline::sample(double t) const
{
    Eigen::VectorXd out;
    sample(t, out);
    return out;
}

TimelinePlayer::TimelinePlayer(const PoseModel& model, const Timeline& timeline, const Mesh& neutral)
    : model_(model)
    , timeline_(timeline)
{
    checkFace(model, neutral, "the face to play the timeline on");
    if (timeline.dim() != 3 * model.fpCount())
        fail("timeline: poses of ", timeline.dim(), " values, the pose model has 3 x ", model.fpCount(), " feature points");
    neutral_ = neutral.V;
}

void TimelinePlayer::frame(double t, Vertices& out)
{
    timeline_.sample(t, fp_);
    mapToMesh(model_.mapping, fp_, mesh_);
    out = neutral_;
    asVector(out) += mesh_;
}

Vertices TimelinePlayer::frame(double t)
{
    Vertices out;
    frame(t, out);
    return out;
}

} // namespace facesketch::pose

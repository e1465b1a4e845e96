#pragma once
// Keyframes and the timeline (thesis 5.5). A keyframe is a completed FP pose (3F displacements,
// pose_data.h) at a time; the FP pose at any time comes from a cardinal spline through the
// keyframes, and each frame's mesh is rebuilt from it by the mapping (mapping.h), as the thesis
// did, not by blending keyframe meshes.
//
// The spline. Keyframes (t_k, p_k), k = 0..N-1, times strictly increasing. On [t_k, t_k+1] with
// h = t_k+1 - t_k and s = (t - t_k) / h, the cubic Hermite curve
//   p(t) = h00(s) p_k + h10(s) h m_k + h01(s) p_k+1 + h11(s) h m_k+1,
//   h00 = 2s^3 - 3s^2 + 1, h10 = s^3 - 2s^2 + s, h01 = -2s^3 + 3s^2, h11 = s^3 - s^2,
// with the cardinal tangents m_k = (1 - c) (p_k+1 - p_k-1) / (t_k+1 - t_k-1) inside and the
// one-sided m_0 = (1 - c) (p_1 - p_0) / (t_1 - t_0), m_N-1 = (1 - c) (p_N-1 - p_N-2) / (t_N-1 -
// t_N-2) at the ends. Tension c in [0, 1]: c = 0 is the Catmull-Rom spline, c = 1 gives zero
// tangents (eases in and out of every keyframe). The curve passes through every keyframe and is
// C1; with two keyframes and c = 0 it is the straight line between them.

#include "pose/pose_model.h"

#include <Eigen/Core>
#include <vector>

namespace facesketch::pose {

struct Keyframe {
    /// Seconds.
    double time = 0.0;
    /// 3F FP displacements (mm), a completed pose.
    Eigen::VectorXd fp;
};

class Timeline {
public:
    /// Sorts the keyframes by time. Throws Error (naming the keyframes at fault) for fewer than
    /// two keyframes, two at the same time, a NaN or infinite time or coordinate, keyframes of
    /// different sizes or of size 0, or a tension outside [0, 1].
    explicit Timeline(std::vector<Keyframe> keyframes, double tension = 0.0);

    double begin() const { return keyframes_.front().time; }
    double end() const { return keyframes_.back().time; }
    double tension() const { return tension_; }
    /// The keyframes in time order.
    const std::vector<Keyframe>& keyframes() const { return keyframes_; }
    /// 3F, the size of every keyframe's FP pose.
    Eigen::Index dim() const { return keyframes_.front().fp.size(); }

    /// The FP pose at time t (3F). Deterministic: the same t always gives the same bits. Throws
    /// Error if t is NaN or outside [begin(), end()].
    Eigen::VectorXd sample(double t) const;
    /// sample into `out` (resized if needed); no allocation once out has its size.
    void sample(double t, Eigen::VectorXd& out) const;

private:
    std::vector<Keyframe> keyframes_;
    /// Tangents m_k, one 3F vector per keyframe.
    std::vector<Eigen::VectorXd> tangents_;
    double tension_ = 0.0;
};

/// Plays a timeline on one face: the frame at time t is neutral + Psi(sample(t)). Holds its
/// scratch vectors, so one frame allocates nothing but its result.
class TimelinePlayer {
public:
    /// Throws Error if the face does not fit the model (pose_model.h checkFace) or the timeline's
    /// poses are not 3F of the model. Keeps references to model and timeline: keep them alive.
    TimelinePlayer(const PoseModel& model, const Timeline& timeline, const Mesh& neutral);

    /// The face at time t (#V by 3, mm) written into `out`. Throws Error as Timeline::sample.
    void frame(double t, Vertices& out);
    Vertices frame(double t);

private:
    const PoseModel& model_;
    const Timeline& timeline_;
    Vertices neutral_;
    Eigen::VectorXd fp_;
    Eigen::VectorXd mesh_;
};

} // namespace facesketch::pose

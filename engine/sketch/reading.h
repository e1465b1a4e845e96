#pragma once
// What a stroke says about the face once it is read: the vertices it pins down and where
// (thesis 4.6.2, 4.8.2). Every mapper (sketch/mapper.h) returns one; the tracking model
// (sketch/tracking.h) turns it into measurements for the face model's conditional inference.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace facesketch::sketch {

/// One vertex a stroke pins down.
struct VertexObservation {
    std::uint32_t vertex = 0;                           ///< in the face model's numbering
    Eigen::Vector3d position = Eigen::Vector3d::Zero(); ///< world, mm
    /// Only the image of `position` in the stroke's view counts (measured with the view's x and
    /// y rows, stats::Observations::addProjectedVertex); its depth is left to the model.
    bool viewPlaneOnly = false;
    /// When not zero (a unit vector in the view plane, world): the direction across the stroke
    /// at its point. Then of the image only the offset across the stroke counts, not the
    /// position along it: a stroke says where a contour runs, not which of its vertices lies
    /// under which point, so a vertex mapped one neighbour along the line is not pulled onto
    /// its neighbour's place. With viewPlaneOnly the observation is that one direction; without
    /// it, that direction and the depth along the view axis.
    Eigen::Vector3d acrossStroke = Eigen::Vector3d::Zero();
    int strokePoint = -1; ///< index of the (densified) stroke point it came from
};

struct StrokeReading {
    /// At most one per vertex, in stroke order.
    std::vector<VertexObservation> observations;
    /// The stroke after densification and projection: screen (pixels) and world (mm) per point.
    std::vector<Eigen::Vector2d> screenPoints;
    std::vector<Eigen::Vector3d> worldPoints;
    /// Per densified point: how many candidates it had, and the candidate it was mapped to
    /// (index into `candidates`, -1 if none).
    std::vector<int> candidateCounts;
    std::vector<int> chosen;
    /// The x and y rows of the view's rotation (for viewPlaneOnly observations).
    Eigen::Matrix<double, 2, 3> viewPlane = Eigen::Matrix<double, 2, 3>::Zero();
    /// Why the reading pins fewer vertices than it has points, when that is worth telling the
    /// user (no candidates under the stroke, the stroke off screen or off the face); empty
    /// otherwise.
    std::string message;
};

} // namespace facesketch::sketch

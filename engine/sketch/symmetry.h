#pragma once
// The left-right mirror map of a face topology, for the symmetry option of sketching: a stroke
// drawn on one half of the face also pins the mirror-image vertices of the other half.
//
// The mirror plane is x = c (the face looks down +z with +y up, docs/conventions.md), c taken
// from the labels (the mean of the midpoints of every landmark pair "NAME_l"/"NAME_r"), else
// from the geometry (the mean x of the vertices). Each vertex is paired with a vertex near its
// mirror image: candidate pairs (the 4 nearest vertices of every mirror image) are taken in
// order of distance, each vertex paired once, so the map is an involution by construction
// (a vertex on the plane pairs with itself). The map is then verified: every pair must lie
// within `tolerance` times the mean edge length of each other's mirror image, and every
// labelled pair must map onto each other.

#include "core/mesh.h"

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace facesketch::sketch {

struct MirrorCheck {
    double planeX = 0;       ///< c, mm
    double meanEdge = 0;     ///< of the face, mm
    double maxDistance = 0;  ///< largest |mirror(x_v) - x_partner(v)|, mm
    double meanDistance = 0; ///< its mean over the vertices, mm
    int selfPaired = 0;      ///< vertices on the plane (their own partner)
    int labelledPairs = 0;   ///< landmark pairs checked
};

class MirrorMap {
public:
    MirrorMap() = default;

    /// Finds and verifies the map of `face` (#V by 3, mm; best the mean face, which is the most
    /// symmetric). `landmarks` are a manifest's landmarks in the face's numbering (names ending
    /// in "_l" and "_r" pair up; others are ignored). Throws Error naming `what`, the worst
    /// vertex and its distance, if a pair lies further than tolerance x mean edge length from
    /// its mirror image, or naming the landmark pair that does not map onto itself.
    static MirrorMap find(const Mesh& face, const std::map<std::string, int>& landmarks, const std::string& what, double tolerance = 0.5);

    Eigen::Index size() const { return static_cast<Eigen::Index>(partner_.size()); }
    std::uint32_t partner(std::uint32_t vertex) const { return partner_[vertex]; }
    const std::vector<std::uint32_t>& partners() const { return partner_; }
    /// x' = reflection() x + offset() mirrors a point through the plane x = c.
    Eigen::Matrix3d reflection() const;
    Eigen::Vector3d offset() const { return { 2 * check_.planeX, 0, 0 }; }
    Eigen::Vector3d mirror(const Eigen::Vector3d& x) const { return reflection() * x + offset(); }
    const MirrorCheck& check() const { return check_; }

private:
    std::vector<std::uint32_t> partner_;
    MirrorCheck check_;
};

/// The landmarks of a manifest renumbered into the skin component (skin.begin becomes 0),
/// those outside the skin left out, for MirrorMap::find on a model's faces.
std::map<std::string, int> skinLandmarks(const std::map<std::string, int>& landmarks, int skinBegin, int skinEnd);

} // namespace facesketch::sketch

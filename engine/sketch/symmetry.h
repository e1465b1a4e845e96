#pragma once
// The left-right mirror map of a face topology, for the symmetry option of sketching: a stroke
// drawn on one half of the face also pins the mirror-image vertices of the other half.
//
// The mirror plane is n . x = c. With labels, n is the mean direction from each landmark
// "NAME_r" to its "NAME_l" and c the median of their midpoints along n (a scan slightly turned
// about y still mirrors right); without, n = +x (the face looks down +z with +y up,
// docs/conventions.md) and c the mean x of the vertices. Each vertex is paired with a vertex near its
// mirror image: candidate pairs (the 4 nearest vertices of every mirror image) are taken in
// order of distance, each vertex paired once, and the few vertices left over are paired among
// themselves the same way, so the map is an involution by construction (a vertex on the plane
// pairs with itself). The plane's c is the median of the labelled pairs' midpoints. The map is then verified: every pair must lie
// within `tolerance` times the vertex's own mean edge length of each other's mirror image, or it is
// dissolved (both vertices left unpaired: mirroring skips them); at most `maxUnpaired` of the
// vertices may end unpaired, and every labelled pair must map onto each other.

#include "core/mesh.h"

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace facesketch::sketch {

struct MirrorCheck {
    Eigen::Vector3d normal = Eigen::Vector3d::UnitX(); ///< of the mirror plane n . x = c
    double planeX = 0;                                 ///< c, mm (the plane x = c when n = +x)
    double meanEdge = 0;                               ///< of the face, mm
    double maxDistance = 0;                            ///< largest |mirror(x_v) - x_partner(v)| over the paired vertices, mm
    double meanDistance = 0;                           ///< its mean over the vertices, mm
    int selfPaired = 0;                                ///< vertices on the plane (their own partner)
    int unpaired = 0;                                  ///< vertices without a partner within the tolerance (mirroring skips them)
    int labelledPairs = 0;                             ///< landmark pairs checked
};

class MirrorMap {
public:
    MirrorMap() = default;

    /// Finds and verifies the map of `face` (#V by 3, mm; best the mean face, which is the most
    /// symmetric). `landmarks` are a manifest's landmarks in the face's numbering (names ending
    /// in "_l" and "_r" pair up; others are ignored). Throws Error naming `what` and the
    /// number of unpaired vertices if more than maxUnpaired of them have no partner within
    /// tolerance x the mean edge length, or naming the landmark pair that does not swap.
    static MirrorMap find(const Mesh& face, const std::map<std::string, int>& landmarks, const std::string& what, double tolerance = 1.0,
        double maxUnpaired = 0.05);

    Eigen::Index size() const { return static_cast<Eigen::Index>(partner_.size()); }
    static constexpr std::uint32_t kNone = 0xffffffffu;
    /// The mirror partner of `vertex`, or kNone for an unpaired vertex.
    std::uint32_t partner(std::uint32_t vertex) const { return partner_[vertex]; }
    const std::vector<std::uint32_t>& partners() const { return partner_; }
    /// x' = reflection() x + offset() mirrors a point through the plane n . x = c:
    /// reflection() = I - 2 n n^T, offset() = 2 c n.
    Eigen::Matrix3d reflection() const;
    Eigen::Vector3d offset() const { return 2 * check_.planeX * check_.normal; }
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

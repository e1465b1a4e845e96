#pragma once
// Pose training data (thesis 5.2): for every posed identity of a dataset, its neutral mesh and
// its poses, as displacements from that neutral in feature-point space ("FP poses") and in mesh
// space ("mesh poses"). The thesis had the 36 poses of one face; we have the same 36 poses of
// many identities, and learning displacements instead of positions makes a pose model apply to
// any face of the topology, also one just sketched (the animation transfer of thesis Ch. 6).
//
// Conventions: a mesh is a 3#V vector (x0, y0, z0, x1, ...) in mm (core/mesh.h asVector); an
// FP pose is a 3F vector, FP i at 3i .. 3i+2, in the order of FeaturePoints::names. A
// displacement is pose minus the same identity's neutral, so the neutral pose is 0.

#include "core/mesh.h"
#include "dataset/dataset.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace facesketch::pose {

/// Orders MPEG-4 FDP names "group.point" numerically: group, then point ("2.1" < "2.2" <
/// "2.10" < "3.1"). Names that do not parse sort after the ones that do, by text.
bool fdpLess(const std::string& a, const std::string& b);

/// True for the FPs a stroke can draw (thesis 5.3: all but the tongue 6.x, the lower teeth 9.10
/// and 9.11, and the inner lips 2.2-2.9): 32 of the 46.
bool isSketchable(const std::string& fdp);

/// The feature points of a topology: F MPEG-4 points, each one vertex (thesis 5.2).
struct FeaturePoints {
    /// F FDP names in fdpLess order; the order of every FP vector.
    std::vector<std::string> names;
    /// F vertex indices into the topology, names[i] -> vertices[i].
    std::vector<int> vertices;

    Eigen::Index size() const { return static_cast<Eigen::Index>(names.size()); }
    /// Index of `name` in names, or -1.
    int index(const std::string& name) const;
    /// The 3F vector of the FP positions of a face: FP i at 3i .. 3i+2 = V.row(vertices[i]).
    /// Throws Error if a vertex lies outside V.
    Eigen::VectorXd gather(const Vertices& V) const;
    /// gather for a face given as a 3#V vector (x0, y0, z0, x1, ...).
    Eigen::VectorXd gatherFlat(const Eigen::Ref<const Eigen::VectorXd>& face) const;
};

/// The manifest's `mpeg4` labels in fdpLess order (46 for a full synthetic set; fewer for an
/// ICT import without --with-mouth). Throws Error naming the dataset if there are fewer than 4.
FeaturePoints featurePoints(const dataset::Manifest& manifest, const std::string& where);

struct PosedIdentity {
    std::string name;
    dataset::Role role = dataset::Role::Train;
};

/// The poses of several identities of one topology. I identities, P poses each (the same P names,
/// "neutral" included), n = I P rows, row i P + p = pose p of identity i.
struct PoseSet {
    FeaturePoints fps;
    int vertexCount = 0;
    Triangles topology;
    /// P pose names in the dataset's order for the first identity.
    std::vector<std::string> poseNames;
    /// I identities with their roles.
    std::vector<PosedIdentity> identities;
    /// I by 3#V neutral meshes (the samples' meshes), mm.
    Eigen::MatrixXd neutrals;
    /// n by 3#V mesh poses: pose minus neutral, mm.
    Eigen::MatrixXd meshDisplacements;
    /// n by 3F FP poses: FP positions of the pose minus those of the neutral, mm.
    Eigen::MatrixXd fpDisplacements;

    Eigen::Index identityCount() const { return static_cast<Eigen::Index>(identities.size()); }
    Eigen::Index poseCount() const { return static_cast<Eigen::Index>(poseNames.size()); }
    Eigen::Index row(Eigen::Index identity, Eigen::Index pose) const { return identity * poseCount() + pose; }
    /// Index of a pose name in poseNames, or -1.
    int poseIndex(const std::string& name) const;
};

/// Loads every identity of the dataset whose role is in `roles` and that has poses. Every such
/// identity must have the pose names of the first one (in any order; rows follow the first
/// one's order). Throws Error naming the dataset and the identity or pose if: the units are not
/// mm, no identity with these roles has poses, an identity lacks a pose or has an extra one,
/// a mesh does not match the manifest (dataset.h loadMesh), or a mesh holds a NaN.
PoseSet loadPoseSet(const dataset::Dataset& dataset, const std::vector<dataset::Role>& roles);

/// The rows of `set` of the identities with `role`, as a new PoseSet (possibly with no
/// identities).
PoseSet selectRole(const PoseSet& set, dataset::Role role);

} // namespace facesketch::pose

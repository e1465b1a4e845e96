#pragma once
// Head assembly (issue 4): the rigid parts of the head (eyeballs, teeth, tongue) follow the
// skin. Each part is stored on the mean head with a set of anchor skin vertices around it
// (stats/head_layout.h); after the skin is reconstructed, the least-squares similarity from
// the anchors' mean positions to their reconstructed positions (geometry/similarity.h, Umeyama
// 1991) moves the part, so an eyeball stays in its socket as the face changes shape.
//
// The layout's structs live in stats/ because the face model file stores them; everything
// that builds or uses a layout is here, with the head model that trains one
// (model/head_model.h).

#include "core/mesh.h"
#include "stats/face_model.h"
#include "stats/head_layout.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace facesketch::model {

/// A part with anchors chosen on the mean head: the `anchorCount` skin vertices nearest the
/// centroid of the part's vertices (all skin vertices if there are fewer), in increasing order.
/// @param[in] vertices  the part's vertices, indices into meanHead
/// @param[in] meanSkin  #S by 3 skin vertices of the mean head (the model's numbering), mm
/// @param[in] meanHead  #V by 3 vertices of the mean head, mm
/// Throws Error naming the part for no vertices, a vertex outside the head, no skin or
/// anchorCount < 1.
stats::RigidPart makeRigidPart(const std::string& name, const std::vector<int>& vertices, const Vertices& meanSkin,
    const Vertices& meanHead, int anchorCount, bool scale = true);

/// The whole head for a skin face: skin vertices from `skin` (3 #S values, laid out x0, y0,
/// z0, x1, ...), each part moved by the similarity fitted from its anchors' mean positions
/// (`meanSkin`, 3 #S values) to their positions in `skin`. Returns #V by 3 vertices (mm) and
/// the layout's topology. Throws Error if the layout is empty (vertexCount 0) or its sizes
/// disagree with the skin.
Mesh assembleHead(const stats::HeadLayout& layout, const Eigen::VectorXd& meanSkin, const Eigen::VectorXd& skin);

/// The whole head for the measurements: stats::reconstruct(), then the rigid parts moved with
/// the skin around them (assembleHead with model.head and model.meanFace). Returns #head
/// vertices by 3 and the head's triangles. Throws Error for a skin-only model.
Mesh reconstructHead(const stats::FaceModel& model, const stats::Observations& observations, const stats::ReconstructOptions& options = {});

} // namespace facesketch::model

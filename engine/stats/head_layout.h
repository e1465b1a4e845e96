#pragma once
// The head beyond the skin, as data: the whole head's size and topology and its rigid parts
// (eyeballs, teeth, tongue), each stored on the mean head with the skin vertices it follows.
//
// Why this lives in stats/ while head assembly lives in model/: a trained stats::FaceModel
// carries its HeadLayout and the face model file (stats/model_file.h) stores and checks it,
// and stats/ must not include model/ (dependencies point one way: model/ builds on stats/).
// So only the plain structs and the consistency check that the file reader needs are here.
// What the layout is for (choosing a part's anchors, moving the parts with a reconstructed
// skin, reconstructing a whole head) is model/head_assembly.h.

#include "core/mesh.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace facesketch::stats {

/// A part of the head that moves as one body with the skin around it.
struct RigidPart {
    std::string name;
    /// Its vertices, indices into the whole head.
    std::vector<int> vertices;
    /// Their positions on the mean head, #vertices by 3 (mm).
    Vertices mean;
    /// Skin vertices (the face model's numbering) whose motion the part follows.
    std::vector<int> anchors;
    /// Similarity (true) or rigid motion (false).
    bool scale = true;
};

/// What the face model needs, beyond the skin, to rebuild the whole head.
struct HeadLayout {
    /// #V of the whole head; 0 if the model knows the skin only.
    int vertexCount = 0;
    /// Head index of the skin's vertex 0; skin vertex v is head vertex skinBegin + v.
    int skinBegin = 0;
    /// #F by 3 triangles of the whole head.
    Triangles topology;
    /// Every head vertex outside the skin belongs to exactly one part.
    std::vector<RigidPart> parts;
};

/// Throws Error naming `where` and the first inconsistency: a part vertex outside the head,
/// inside the skin or in two parts, a head vertex in no part, an anchor outside [0, skinVertices),
/// a mean of the wrong size, a triangle index outside the head.
void validateHeadLayout(const HeadLayout& layout, Eigen::Index skinVertices, const std::string& where);

} // namespace facesketch::stats

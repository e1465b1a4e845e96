#pragma once
// The 36 pose recipes of the synthetic set (thesis 5.2 used 36 FaceGen poses): neutral, 21
// expressions and 14 visemes. A recipe says how the generator makes a pose (the deformers in
// FaceActions, face_generator.h); the pose is the mesh it gives for one identity (manifest.h
// Pose). The ICT import uses the same 36 names with recipes of its own (import_ict.h).
// Expressions follow the usual FACS reading of each emotion (e.g. anger = brow lowerer, lid
// tightener, lip presser); visemes follow the mouth shapes of the 14 MPEG-4 / Oculus viseme
// classes (PP, FF, TH, DD, kk, CH, SS, nn, RR, aa, E, I, O, U).

#include "dataset/synth/face_generator.h"

#include <string>
#include <vector>

namespace facesketch::dataset {

/// How to make one pose: its name (the pose's name in the manifest) and the deformers.
struct PoseRecipe {
    std::string name; ///< file-name safe, e.g. "smile_open", "viseme_aa"
    bool viseme = false;
    FaceActions actions;
};

/// All 36 recipes; the first is "neutral" (no actions).
const std::vector<PoseRecipe>& poseRecipes();

} // namespace facesketch::dataset

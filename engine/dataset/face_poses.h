#pragma once
// The 36 poses of the synthetic set (thesis 5.2 used 36 FaceGen poses): neutral, 21
// expressions and 14 visemes, each a recipe of the muscle-like deformers in FaceActions.
// Expressions follow the usual FACS reading of each emotion (e.g. anger = brow lowerer, lid
// tightener, lip presser); visemes follow the mouth shapes of the 14 MPEG-4 / Oculus viseme
// classes (PP, FF, TH, DD, kk, CH, SS, nn, RR, aa, E, I, O, U).

#include "dataset/face_model.h"

#include <string>
#include <vector>

namespace facesketch::dataset {

struct PoseRecipe {
    std::string name; ///< file-name safe, e.g. "smile_open", "viseme_aa"
    bool viseme = false;
    FaceActions actions;
};

/// All 36 poses; the first is "neutral" (no actions).
const std::vector<PoseRecipe>& poseRecipes();

} // namespace facesketch::dataset

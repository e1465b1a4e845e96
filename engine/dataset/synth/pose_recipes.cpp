#include "dataset/synth/pose_recipes.h"

namespace facesketch::dataset {

namespace {

PoseRecipe pose(const char* name, bool viseme, FaceActions a)
{
    return { name, viseme, a };
}

std::vector<PoseRecipe> makeRecipes()
{
    std::vector<PoseRecipe> out;
    FaceActions a;
    out.push_back(pose("neutral", false, a));

    a = {};
    a.browLower = 4.5;
    a.lidClose[0] = a.lidClose[1] = 0.25;
    a.lowerLidRaise = 1.5;
    a.lipPress = 0.8;
    a.cornerDepress[0] = a.cornerDepress[1] = 1.5;
    a.noseWrinkle = 1.0;
    out.push_back(pose("anger", false, a));
    a = {};
    a.noseWrinkle = 3;
    a.upperLipRaise[0] = a.upperLipRaise[1] = 3;
    a.browLower = 2.5;
    a.lowerLidRaise = 1.5;
    a.cornerDepress[0] = a.cornerDepress[1] = 2;
    a.cheekRaise = 1;
    out.push_back(pose("disgust", false, a));
    a = {};
    a.browInnerRaise = 6;
    a.browOuterRaise = 3;
    a.lidWide = 0.35;
    a.mouthStretch = 4;
    a.jawOpen = 6;
    a.lipPart = 1.5;
    out.push_back(pose("fear", false, a));
    a = {};
    a.browInnerRaise = 5;
    a.browOuterRaise = -1;
    a.cornerDepress[0] = a.cornerDepress[1] = 3.5;
    a.lidClose[0] = a.lidClose[1] = 0.2;
    a.lowerLipDepress = 0;
    a.lipPress = 0.2;
    out.push_back(pose("sadness", false, a));
    a = {};
    a.browInnerRaise = 8;
    a.browOuterRaise = 8;
    a.lidWide = 0.45;
    a.jawOpen = 16;
    a.lipPart = 2;
    out.push_back(pose("surprise", false, a));
    a = {};
    a.cornerPull[0] = a.cornerPull[1] = 7;
    a.cheekRaise = 2.5;
    a.lowerLidRaise = 1.2;
    a.lipPress = 0.2;
    out.push_back(pose("smile_closed", false, a));
    a = {};
    a.cornerPull[0] = a.cornerPull[1] = 8;
    a.cheekRaise = 3;
    a.lowerLidRaise = 1.5;
    a.jawOpen = 8;
    a.upperLipRaise[0] = a.upperLipRaise[1] = 2;
    a.lipPart = 2;
    out.push_back(pose("smile_open", false, a));
    a = {};
    a.pucker = 0.9;
    a.lipsForward = 5;
    a.lipPress = 0.3;
    out.push_back(pose("pucker", false, a));
    a = {};
    a.pucker = 0.6;
    a.lipsForward = 4.5;
    a.lipPart = 4;
    a.jawOpen = 5;
    out.push_back(pose("funnel", false, a));
    a = {};
    a.jawOpen = 18;
    a.lipPart = 1;
    out.push_back(pose("jaw_open", false, a));
    a = {};
    a.upperLipRaise[0] = 4;
    a.noseWrinkle = 1.5;
    a.cornerPull[0] = 1.5;
    a.lidClose[0] = 0.2;
    out.push_back(pose("sneer_right", false, a));
    a = {};
    a.upperLipRaise[1] = 4;
    a.noseWrinkle = 1.5;
    a.cornerPull[1] = 1.5;
    a.lidClose[1] = 0.2;
    out.push_back(pose("sneer_left", false, a));
    a = {};
    a.browInnerRaise = 7;
    a.browOuterRaise = 7;
    a.lidWide = 0.15;
    out.push_back(pose("brow_raise", false, a));
    a = {};
    a.browLower = 5;
    out.push_back(pose("brow_lower", false, a));
    a = {};
    a.lidClose[0] = a.lidClose[1] = 0.45;
    a.lowerLidRaise = 2.0;
    a.cheekRaise = 1.5;
    a.browLower = 1;
    out.push_back(pose("squint", false, a));
    a = {};
    a.lidClose[0] = a.lidClose[1] = 1.0;
    out.push_back(pose("blink", false, a));
    a = {};
    a.lidWide = 0.5;
    a.browInnerRaise = 2;
    a.browOuterRaise = 2;
    out.push_back(pose("eyes_wide", false, a));
    a = {};
    a.cheekPuff = 6;
    a.lipPress = 0.4;
    a.lipsForward = 1;
    out.push_back(pose("cheek_puff", false, a));
    a = {};
    a.cornerDepress[0] = a.cornerDepress[1] = 4;
    a.browLower = 3;
    a.lowerLipDepress = 0.5;
    out.push_back(pose("frown", false, a));
    a = {};
    a.cornerPull[1] = 8;
    a.cheekRaise = 1.2;
    out.push_back(pose("smile_left", false, a));
    a = {};
    a.cornerPull[0] = 8;
    a.cheekRaise = 1.2;
    out.push_back(pose("smile_right", false, a));

    // Visemes.
    a = {};
    a.lipPress = 0.7;
    a.lipsForward = 0.5;
    out.push_back(pose("viseme_PP", true, a));
    a = {};
    a.jawOpen = 3;
    a.lowerLipTuck = 1.5;
    a.upperLipRaise[0] = a.upperLipRaise[1] = 1;
    out.push_back(pose("viseme_FF", true, a));
    a = {};
    a.jawOpen = 6;
    a.lipPart = 1.5;
    a.tongueForward = 2.5;
    a.tongueUp = 1;
    out.push_back(pose("viseme_TH", true, a));
    a = {};
    a.jawOpen = 5;
    a.lipPart = 1.5;
    a.tongueUp = 3;
    out.push_back(pose("viseme_DD", true, a));
    a = {};
    a.jawOpen = 7;
    a.lipPart = 2;
    a.tongueForward = -3;
    a.tongueUp = 2;
    out.push_back(pose("viseme_kk", true, a));
    a = {};
    a.jawOpen = 4;
    a.pucker = 0.4;
    a.lipsForward = 3.5;
    a.lipPart = 2.5;
    out.push_back(pose("viseme_CH", true, a));
    a = {};
    a.jawOpen = 2;
    a.lipPart = 1.5;
    a.mouthStretch = 2.5;
    out.push_back(pose("viseme_SS", true, a));
    a = {};
    a.jawOpen = 4;
    a.lipPart = 1;
    a.tongueUp = 3;
    out.push_back(pose("viseme_nn", true, a));
    a = {};
    a.jawOpen = 5;
    a.pucker = 0.35;
    a.lipsForward = 2.5;
    a.lipPart = 2;
    out.push_back(pose("viseme_RR", true, a));
    a = {};
    a.jawOpen = 17;
    a.lipPart = 2;
    out.push_back(pose("viseme_aa", true, a));
    a = {};
    a.jawOpen = 8;
    a.mouthStretch = 4;
    a.lipPart = 2;
    out.push_back(pose("viseme_E", true, a));
    a = {};
    a.jawOpen = 5;
    a.mouthStretch = 5;
    a.cornerPull[0] = a.cornerPull[1] = 1.5;
    a.lipPart = 1.5;
    out.push_back(pose("viseme_I", true, a));
    a = {};
    a.jawOpen = 12;
    a.pucker = 0.6;
    a.lipsForward = 3.5;
    a.lipPart = 2.5;
    out.push_back(pose("viseme_O", true, a));
    a = {};
    a.jawOpen = 4;
    a.pucker = 0.95;
    a.lipsForward = 5.5;
    a.lipPart = 1;
    out.push_back(pose("viseme_U", true, a));
    return out;
}

} // namespace

const std::vector<PoseRecipe>& poseRecipes()
{
    static const std::vector<PoseRecipe> recipes = makeRecipes();
    return recipes;
}

} // namespace facesketch::dataset

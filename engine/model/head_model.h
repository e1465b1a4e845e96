#pragma once
// The face model of a whole dataset (`facesketch train`): the statistical skin model of
// stats/face_model.h trained on the dataset's skin, plus the dataset's full topology and its
// rigid parts (eyeballs, teeth, tongue: every component other than the skin), each following
// the skin around it (model/head_assembly.h), so a reconstruction is a complete head.

#include "dataset/dataset.h"
#include "stats/face_model.h"

#include <string>

namespace facesketch::model {

struct HeadModelOptions {
    stats::FaceModelOptions face;
    /// Anchor skin vertices per rigid part: the ones nearest the part's centre on the mean head
    /// (for an eyeball, the lids and the socket around it).
    int anchors = 24;
    /// Rigid parts follow their anchors by a similarity (true) or a rigid motion (false).
    bool scale = true;
};

/// The triangles of the manifest's topology whose three vertices are skin, renumbered so that
/// skin.begin becomes 0 (the face model's numbering). #F_skin by 3.
Triangles skinTriangles(const dataset::Manifest& manifest);

/// The skin vertex (model numbering) of a landmark. Throws Error naming the landmark if the
/// manifest lacks it or it is not on the skin.
int skinLandmark(const dataset::Manifest& manifest, const std::string& name);

/// Trains on the dataset's `train` samples: the skin model (nose tip: landmark "prn") and a
/// rigid part per non-skin component, plus one part "unassigned" for vertices in no component.
/// Throws Error for a dataset without "prn", with fewer than 4 train samples, or whose units
/// are not mm.
stats::FaceModel trainHeadModel(
    const dataset::Dataset& dataset, const HeadModelOptions& options = {}, const stats::TrainProgress& progress = {});

/// Throws Error naming `where` if the model was not trained on this dataset's topology (vertex
/// count, skin range).
void requireModelFits(const stats::FaceModel& model, const dataset::Manifest& manifest, const std::string& where);

} // namespace facesketch::model

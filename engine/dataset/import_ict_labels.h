#pragma once
// Internal to engine/dataset: the labelling rules of the ICT import (import_ict.h, "Landmarks",
// "Contours", "MPEG-4"), applied to a region's neutral in mm. import_ict.cpp cuts the region
// and calls these; they only fill fields of the manifest they are given.

#include "core/mesh.h"
#include "dataset/manifest.h"

#include <Eigen/Core>
#include <vector>

namespace facesketch::dataset::ict {

/// Landmarks, contours, skin MPEG-4 points and the hidden nostril insides (added to
/// m.excluded) of the skin [0, skinEnd) of the neutral V (#V by 3, mm), whose triangles are
/// m.topology. `pie` holds the 68 Multi-PIE points as vertex indices of V; `prn` is the nose
/// tip (robustTip). Throws Error if a rule finds no vertex (region too small).
void labelSkin(Manifest& m, const Vertices& V, const std::vector<int>& pie, int skinEnd, int prn);

/// prn: among the skin vertices within 10 mm of Multi-PIE point 30, the one that lies within
/// 3 mm of the most forward skin vertex for the most of 64 identities of seed 0 (ties: the
/// smaller mean distance). `modes` is IctModel::identityModes.
int robustTip(const Vertices& neutral, const Eigen::MatrixXd& modes, const std::vector<int>& pie, int skinEnd);

/// MPEG-4 9.10 and 9.11 on the lower teeth (each tooth a connected part of the component).
void labelLowerTeeth(Manifest& m, const Vertices& V, const Component& teeth);

/// MPEG-4 group 6 on the tongue: tip, dorsum centre and the two borders at mid depth.
void labelTongue(Manifest& m, const Vertices& V, const Component& tongue);

} // namespace facesketch::dataset::ict

#pragma once
// A made-up animation with known frames for the glTF export tests: a 642-vertex sphere "face"
// bent by a different nonlinear displacement in each of 12 frames (1/24 s apart, so no frame is
// a linear blend of the others), and one rigid part, "eye", turning, growing and moving.
// Shared by tests/io/gltf_export.cpp and the gltf_sample program the real-client tests run.

#include "geometry/similarity.h"
#include "io/gltf_export.h"

#include <nlohmann/json.hpp>

namespace facesketch::test {

GltfAnimation makeGltfTestAnimation();

/// The similarity that animation.parts[part] applies at frame k (from its TRS).
Similarity partMotion(const GltfAnimation& animation, std::size_t part, std::size_t k);

/// The real clients' expectations (tools/gltf/three-check.mjs): at the times of frames 3, 5 and
/// 10, three face vertices with the largest displacement from rest and two vertices of each
/// part, where FaceSketch puts them (mm).
nlohmann::json gltfExpectations(const GltfAnimation& animation);

} // namespace facesketch::test

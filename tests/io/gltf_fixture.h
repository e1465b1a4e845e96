#pragma once
// A made-up animation with known frames for the glTF export tests: a 642-vertex sphere "face"
// bent by a different nonlinear displacement in each of 12 frames (1/24 s apart, so no frame is
// a linear blend of the others), and one rigid part, "eye", turning, growing and moving.
// Shared by tests/io/gltf_export.cpp and the gltf_sample program the real-client tests run.

#include "geometry/similarity.h"
#include "io/gltf_export.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

namespace facesketch::test {

GltfAnimation makeGltfTestAnimation();

/// The similarity that animation.parts[part] applies at frame k (from its TRS).
Similarity partMotion(const GltfAnimation& animation, std::size_t part, std::size_t k);

/// The real clients' expectations (tools/gltf/three-check.mjs): at the times of frames 3, 5 and
/// 10, three face vertices with the largest displacement from rest and two vertices of each
/// part, where FaceSketch puts them (mm).
nlohmann::json gltfExpectations(const GltfAnimation& animation);

/// Reading an exported .glb back (tinygltf), as a client would; Error for anything unexpected.
tinygltf::Model loadGlb(const std::filesystem::path& path);
/// An accessor's floats (tightly packed, as writeGlb writes them), and as #V by 3 rows.
std::vector<float> floatsOf(const tinygltf::Model& model, int accessor);
Vertices asRows(const std::vector<float>& values);
int nodeNamed(const tinygltf::Model& model, const std::string& name);
/// The sampler of node `node`'s channel for `path` ("weights", "translation", ...).
const tinygltf::AnimationSampler& samplerFor(const tinygltf::Model& model, int node, const std::string& path);
/// What a client shows of the node "face" at key k plus a fraction a of the way to key k + 1
/// (LINEAR weights, glTF 2.0 3.11): its base positions plus the weighted morph targets.
Vertices morphedFace(const tinygltf::Model& model, std::size_t k, double a);

} // namespace facesketch::test

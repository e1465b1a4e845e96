#pragma once
// A small synthetic world for the stroke-reading tests: a low-resolution synthetic dataset,
// a face model trained on its train faces, the contour-role faces as candidate faces, the
// skin's vertex flags and labelled contours in the model's numbering. Built once per process and
// seed (ctest runs each test case in its own process); seed 1 unless a test asks for another
// draw of faces.

#include "dataset/manifest.h"
#include "stats/face_model.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace facesketch::test {

struct SketchWorld {
    dataset::Manifest manifest;
    stats::FaceModel model;
    std::vector<Mesh> candidateFaces;                 ///< contour-role faces, skin only
    std::vector<Mesh> testFaces;                      ///< test-role faces, skin only
    std::vector<std::uint32_t> flags;                 ///< VertexFlag per model vertex
    std::map<std::string, std::vector<int>> contours; ///< labelled contours, model numbering
    Mesh mean;                                        ///< the model's mean face
};

const SketchWorld& sketchWorld(std::uint64_t seed = 1);

} // namespace facesketch::test

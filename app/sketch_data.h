#pragma once
// What `facesketch sketch`, `eval strokes`, `strokes simulate` and `bench sketch` share: what
// they load from a model and its dataset (everything on the model's skin topology), and the
// options that say how simulated strokes are drawn.

#include "dataset/dataset.h"
#include "geometry/camera.h"
#include "sketch/simulate.h"
#include "stats/face_model.h"

#include <CLI/CLI.hpp>
#include <map>
#include <string>
#include <vector>

namespace facesketch::app {

struct SketchData {
    dataset::Dataset dataset;
    Triangles triangles;                              ///< the skin topology
    std::vector<std::uint32_t> flags;                 ///< VertexFlag per skin vertex
    std::map<std::string, std::vector<int>> contours; ///< labelled contours, skin numbering
    std::map<std::string, int> landmarks;             ///< skin numbering
    std::vector<Mesh> candidateFaces;                 ///< train then contour faces (the cloud)
    std::vector<std::string> trainNames;              ///< names of the train faces (first in candidateFaces)
    std::vector<std::string> testNames;
    std::vector<Mesh> testFaces;
};

/// Opens the dataset and loads its skin faces by role; `model`, if given, must fit it
/// (model::requireModelFits). Throws Error naming the folder.
SketchData loadSketchData(const std::string& datasetFolder, const stats::FaceModel* model);

/// The skin meshes of one role (names appended to `names` if given).
std::vector<Mesh> skinFaces(const dataset::Dataset& ds, dataset::Role role, const Triangles& F, std::vector<std::string>* names);

/// The model's mean face as a mesh.
Mesh meanMesh(const stats::FaceModel& model);

/// "front,profile,34" or "front;profile;AZ,EL": views by name; two numbers in a row are one
/// AZ,EL view, a lone number ("34") a name. Throws Error naming a view parseView rejects.
std::vector<std::pair<std::string, ViewAngles>> parseViewList(const std::string& text);

/// Declares on `cmd` the options of how a simulated hand draws, bound to `style`'s fields:
/// --noise, --extreme, --reversed, --wander and --wander-length (the same names, ranges and
/// defaults for `strokes simulate` and `eval strokes`).
void addStrokeStyleOptions(CLI::App* cmd, sketch::SimulateOptions& style);

} // namespace facesketch::app

#pragma once
// What the user sees of a stroke's reading (issue 12; thesis 4.11.2, figs. 4.35 and 4.56):
// the interpreted stroke, i.e. the rebuilt face's curve through the vertices the stroke mapped
// to, drawn in the stroke's view so an extreme stroke shows how it was understood; and the
// training faces most like the result, for looking a face up by sketching it.

#include "core/mesh.h"
#include "geometry/camera.h"
#include "sketch/reading.h"

#include <Eigen/Core>
#include <span>
#include <vector>

namespace facesketch::sketch {

struct InterpretedStroke {
    std::vector<std::uint32_t> vertices; ///< the mapped vertices, in stroke order
    std::vector<Eigen::Vector3d> world;  ///< their positions on the rebuilt face, mm
    std::vector<Eigen::Vector2d> screen; ///< and in the stroke's view, pixels
};

/// The mapped vertices of `reading` ordered by the stroke point they came from (ties by
/// vertex), at their positions on `face` (#V by 3, mm) and projected by `camera` (the stroke's
/// view). Throws Error for an observed vertex outside the face.
InterpretedStroke interpretStroke(const StrokeReading& reading, const Mesh& face, const Camera& camera);

/// The k faces of `faces` nearest `face` by mean per-vertex distance (mm), nearest first, as
/// (index, distance). Throws Error for a face of another vertex count (naming its index).
/// A span, so that a caller can search a prefix of its faces (the training ones) without copying.
std::vector<std::pair<int, double>> mostSimilarFaces(const Mesh& face, std::span<const Mesh> faces, int k);

} // namespace facesketch::sketch

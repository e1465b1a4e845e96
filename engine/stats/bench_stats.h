#pragma once
// Micro benchmarks of the statistics core, run by `facesketch bench`. Synthetic data at the
// size of a high-resolution face (6,000 vertices, d = 18,000), fixed seeds.

#include <ostream>

namespace facesketch::stats {

/// Prints one line per measurement, "name value unit", e.g. "conditional_6000v_ms 0.8 ms":
///   conditional_6000v_ms     one infer() on K = 3, q = 30, 15% of the vertices seen in 3D
///   conditional2d_6000v_ms   the same with every observed vertex seen in 2D only
///   face_reconstruct_6000v_ms             reconstruct() with 15% of the vertices seen:
///                                         41 segments, clean-up and correlation, blended
///   face_reconstruct_one_region_6000v_ms  the same from one region's vertices only
///   mppca_fit_6000v_ms       fitMppca on n = 200 faces, K = 3, q = 20
/// Takes a few seconds on one core.
void benchStats(std::ostream& out);

} // namespace facesketch::stats

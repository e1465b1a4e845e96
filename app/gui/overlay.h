#pragma once
// The sketchability overlay (thesis 4.11.2): where in the current view a stroke can be read,
// shown as the density of the contour candidate cloud (contours/candidates.h, 4.4) over the
// training and contour faces, as a translucent heat image over the face. A stroke over a hot
// region has many candidates; over a cold or clear one it pins little or nothing.

#include "contours/candidates_gpu.h"
#include "contours/curvature_gpu.h"
#include "core/mesh.h"
#include "io/png.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

namespace facesketch::gui {

struct HeatOptions {
    /// Candidates are counted in square cells of this many pixels.
    int cellPx = 4;
    /// Gaussian smoothing of the counts, in pixels (about the mapper's candidate radius).
    double sigmaPx = 6.0;
    /// Cells below this fraction of the peak density stay clear.
    double clearBelow = 0.03;
    /// Opacity at the peak; the opacity grows with the density from a quarter of it.
    double maxAlpha = 0.7;
};

/// The heat image (RGBA, width x height pixels) of the candidates' screen positions: per cell the
/// count, smoothed, divided by the peak and coloured blue (low) to red (high)
/// (render/colormap.h) with opacity rising with density; clear where there are no candidates.
/// Throws Error for a non-positive size or cell.
Image heatImage(const std::vector<Candidate>& candidates, int width, int height, const HeatOptions& options = {});

/// The candidate cloud of a set of faces on one topology, for any view: the one-time curvature
/// pass (cached in `cacheFolder`, contours/curvature_cache.h; empty: not cached) and a
/// GpuCandidates. Built on a worker thread if the device is only used there meanwhile.
class CandidateCloud {
public:
    CandidateCloud(gpu::Device& device, const std::vector<Mesh>& faces, const std::vector<std::uint32_t>& flags,
        const std::filesystem::path& cacheFolder);
    ~CandidateCloud();
    /// Every face's candidates seen by `camera` inside its viewport, with the default thresholds
    /// for the topology (as the stroke reader uses).
    std::vector<Candidate> candidates(const Camera& camera);
    int faces() const { return faces_; }

private:
    std::unique_ptr<GpuCurvature> curvature_;
    std::unique_ptr<GpuCandidates> cloud_;
    ContourParams params_;
    int faces_ = 0;
};

} // namespace facesketch::gui

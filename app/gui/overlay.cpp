#include "gui/overlay.h"

#include "contours/curvature_cache.h"
#include "core/error.h"
#include "render/colormap.h"

#include <algorithm>
#include <cmath>

namespace facesketch::gui {

Image heatImage(const std::vector<Candidate>& candidates, int width, int height, const HeatOptions& options)
{
    if (width <= 0 || height <= 0)
        fail("overlay: image size ", width, "x", height, " must be positive");
    if (options.cellPx <= 0 || std::isnan(options.sigmaPx) || options.sigmaPx < 0)
        fail("overlay: cell ", options.cellPx, " px and sigma ", options.sigmaPx, " px must be positive");
    const int cw = (width + options.cellPx - 1) / options.cellPx, ch = (height + options.cellPx - 1) / options.cellPx;
    std::vector<double> count(static_cast<size_t>(cw) * ch, 0.0);
    for (const Candidate& c : candidates) {
        if (!(c.screen[0] >= 0 && c.screen[1] >= 0 && c.screen[0] < width && c.screen[1] < height))
            continue;
        const int x = static_cast<int>(c.screen[0]) / options.cellPx, y = static_cast<int>(c.screen[1]) / options.cellPx;
        count[static_cast<size_t>(y) * cw + x] += 1;
    }
    // Separable Gaussian over the cells.
    const double sigma = options.sigmaPx / options.cellPx;
    const int r = static_cast<int>(std::ceil(3 * sigma));
    std::vector<double> kernel(static_cast<size_t>(2 * r + 1));
    for (int i = -r; i <= r; ++i)
        kernel[static_cast<size_t>(i + r)] = sigma > 0 ? std::exp(-0.5 * i * i / (sigma * sigma)) : 1.0;
    auto blur = [&](const std::vector<double>& in, bool horizontal) {
        std::vector<double> out(in.size(), 0.0);
        for (int y = 0; y < ch; ++y)
            for (int x = 0; x < cw; ++x) {
                double s = 0;
                for (int i = -r; i <= r; ++i) {
                    const int xx = horizontal ? x + i : x, yy = horizontal ? y : y + i;
                    if (xx >= 0 && yy >= 0 && xx < cw && yy < ch)
                        s += kernel[static_cast<size_t>(i + r)] * in[static_cast<size_t>(yy) * cw + xx];
                }
                out[static_cast<size_t>(y) * cw + x] = s;
            }
        return out;
    };
    const std::vector<double> density = blur(blur(count, true), false);
    const double peak = *std::max_element(density.begin(), density.end());

    Image image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<size_t>(width) * height * 4, 0);
    if (!(peak > 0))
        return image;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double t = density[static_cast<size_t>(y / options.cellPx) * cw + x / options.cellPx] / peak;
            if (t < options.clearBelow)
                continue;
            const glm::vec4 c = blueToRed(t);
            std::uint8_t* p = &image.pixels[(static_cast<size_t>(y) * width + x) * 4];
            p[0] = static_cast<std::uint8_t>(std::lround(255 * c.r));
            p[1] = static_cast<std::uint8_t>(std::lround(255 * c.g));
            p[2] = static_cast<std::uint8_t>(std::lround(255 * c.b));
            p[3] = static_cast<std::uint8_t>(std::lround(255 * options.maxAlpha * (0.25 + 0.75 * t)));
        }
    return image;
}

CandidateCloud::CandidateCloud(
    gpu::Device& device, const std::vector<Mesh>& faces, const std::vector<std::uint32_t>& flags, const std::filesystem::path& cacheFolder)
{
    if (faces.empty())
        fail("overlay: no candidate faces");
    const Mesh& first = faces.front();
    std::vector<float> positions;
    positions.reserve(faces.size() * static_cast<size_t>(first.V.rows()) * 3);
    for (size_t i = 0; i < faces.size(); ++i) {
        if (faces[i].V.rows() != first.V.rows())
            fail("overlay: candidate face ", i, " has ", faces[i].V.rows(), " vertices, the first ", first.V.rows());
        for (Eigen::Index v = 0; v < faces[i].V.rows(); ++v)
            for (int k = 0; k < 3; ++k)
                positions.push_back(static_cast<float>(faces[i].V(v, k)));
    }
    curvature_ = std::make_unique<GpuCurvature>(device, first.F, first.V.rows());
    curvature_->setPositions(positions);
    runCurvatureCached(*curvature_, first.F, positions, cacheFolder);
    cloud_ = std::make_unique<GpuCandidates>(device, *curvature_, flags);
    params_.silhouetteThreshold = defaultSilhouetteThreshold(first.V.rows());
    params_.featureSize = meanEdgeLength(first);
    faces_ = static_cast<int>(faces.size());
}

CandidateCloud::~CandidateCloud() = default;

std::vector<Candidate> CandidateCloud::candidates(const Camera& camera)
{
    ContourParams p = params_;
    p.rect[0] = 0;
    p.rect[1] = 0;
    p.rect[2] = camera.width - 1;
    p.rect[3] = camera.height - 1;
    return cloud_->build(camera, p);
}

} // namespace facesketch::gui

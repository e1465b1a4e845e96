#include "sketch/mapper.h"

#include "contours/candidates_gpu.h"
#include "contours/curvature_gpu.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "geometry/graph.h"
#include "geometry/mesh_batch.h"
#include "sketch/mappers.h"
#include "sketch/projection.h"
#include "sketch/stroke_candidates.h"

#include <cmath>
#include <optional>

namespace facesketch::sketch {

const char* mapperName(MapperKind kind)
{
    switch (kind) {
    case MapperKind::Nearest:
        return "nearest";
    case MapperKind::Heuristic:
        return "heuristic";
    case MapperKind::Hmm:
        return "hmm";
    case MapperKind::Simple:
        return "simple";
    }
    return "unknown";
}

MapperKind parseMapper(const std::string& text)
{
    for (MapperKind k : { MapperKind::Nearest, MapperKind::Heuristic, MapperKind::Hmm, MapperKind::Simple })
        if (text == mapperName(k))
            return k;
    fail("mapper '", text, "' is none of nearest, heuristic, hmm, simple");
}

void MapperParams::validate() const
{
    auto positive = [](const char* name, double v) {
        if (!std::isfinite(v) || !(v > 0))
            fail("mapper parameter ", name, " = ", v, " must be positive and finite");
    };
    auto nonNegative = [](const char* name, double v) {
        if (!std::isfinite(v) || !(v >= 0))
            fail("mapper parameter ", name, " = ", v, " must be non-negative and finite");
    };
    positive("densifyGapPx", densifyGapPx);
    if (!std::isfinite(splineTension) || splineTension < 0 || splineTension > 1)
        fail("mapper parameter splineTension = ", splineTension, " must be in [0, 1]");
    positive("tauMm", tauMm);
    positive("candidateRadiusTau", candidateRadiusTau);
    positive("depthToleranceMm", depthToleranceMm);
    if (maxCandidatesPerPoint < 1)
        fail("mapper parameter maxCandidatesPerPoint = ", maxCandidatesPerPoint, " must be at least 1");
    positive("sigmaS", sigmaS);
    positive("sigmaDTau", sigmaDTau);
    positive("sigmaC", sigmaC);
    positive("sigmaStroke", sigmaStroke);
    positive("sigmaSkelTau", sigmaSkelTau);
    nonNegative("unreachableHops", unreachableHops);
    nonNegative("lambda", lambda);
    nonNegative("alpha", alpha);
    nonNegative("beta", beta);
    nonNegative("heuristicEndpointRadiusTau", heuristicEndpointRadiusTau);
}

namespace {
constexpr int kRings = 4; // 4.8.4: k = 4
} // namespace

struct StrokeReader::Impl {
    Impl(gpu::Device& device, const stats::FaceModel& model, const std::vector<Mesh>& faces, std::vector<std::uint32_t> flagsIn)
        : flags(std::move(flagsIn))
        , curvature(device, model.triangles, model.vertexCount())
        , rings(model.triangles, model.vertexCount(), kRings)
        , device(device)
    {
        curvature.setPositions(meshMajorPositions(faces));
        curvature.run();
        cloud.emplace(device, curvature, flags);
        Mesh mean;
        mean.F = model.triangles;
        mean.V.resize(model.vertexCount(), 3);
        for (Eigen::Index v = 0; v < model.vertexCount(); ++v)
            mean.V.row(v) = model.meanFace.segment<3>(3 * v).transpose();
        featureSize = meanEdgeLength(mean);
    }

    std::vector<std::uint32_t> flags;
    GpuCurvature curvature;
    std::optional<GpuCandidates> cloud;
    RingDistances rings;
    gpu::Device& device;
    double featureSize = 1;
    // The simple mapper's own-contour pass: one mesh (the current face), made on first use.
    std::unique_ptr<GpuCurvature> ownCurvature;
    std::optional<GpuCandidates> ownCloud;
};

StrokeReader::StrokeReader(
    gpu::Device& device, const stats::FaceModel& model, const std::vector<Mesh>& candidateFaces, std::vector<std::uint32_t> flags)
    : model_(model)
{
    const Eigen::Index nv = model.vertexCount();
    if (candidateFaces.empty())
        fail("StrokeReader: no candidate faces");
    for (std::size_t i = 0; i < candidateFaces.size(); ++i)
        if (candidateFaces[i].V.rows() != nv || candidateFaces[i].F.rows() != model.triangles.rows())
            fail("StrokeReader: candidate face ", i, " has ", candidateFaces[i].V.rows(), " vertices and ", candidateFaces[i].F.rows(),
                " triangles; the model has ", nv, " and ", model.triangles.rows());
    if (!flags.empty() && static_cast<Eigen::Index>(flags.size()) != nv)
        fail("StrokeReader: ", flags.size(), " vertex flags for a model of ", nv, " vertices");
    impl_ = std::make_unique<Impl>(device, model, candidateFaces, std::move(flags));
}

StrokeReader::~StrokeReader() = default;

StrokeReading StrokeReader::read(const Stroke& stroke, const Mesh& currentFace, MapperKind kind, const MapperParams& params)
{
    validateStroke(stroke, "stroke");
    params.validate();
    const Eigen::Index nv = model_.vertexCount();
    if (currentFace.V.rows() != nv || currentFace.F.rows() != model_.triangles.rows())
        fail("stroke: the current face has ", currentFace.V.rows(), " vertices and ", currentFace.F.rows(), " triangles; the model has ",
            nv, " and ", model_.triangles.rows());
    validateMesh(currentFace, "stroke: the current face");

    Stopwatch clock;
    const Camera camera = orbitCamera(stroke.view);
    const ProjectedStroke projected = projectStroke(stroke, camera, currentFace, params.densifyGapPx, params.splineTension);
    StrokeReading reading;
    reading.screenPoints = projected.screen;
    reading.worldPoints = projected.world;
    reading.viewPlane = viewPlaneRows(camera);
    const std::size_t n = projected.screen.size();
    reading.candidateCounts.assign(n, 0);
    reading.chosen.assign(n, -1);

    const Eigen::Vector3d centre = 0.5 * (currentFace.V.colwise().minCoeff() + currentFace.V.colwise().maxCoeff()).transpose();
    const double tau = params.tauMm * pixelsPerMm(camera, centre);
    const double radiusPx = params.candidateRadiusTau * tau;

    ContourParams contour;
    contour.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    contour.featureSize = impl_->featureSize;
    const double ppmm = pixelsPerMm(camera, centre);
    if (!strokeBox(contour, camera, projected.screen, projected.world, radiusPx, std::hypot(radiusPx / ppmm, params.depthToleranceMm))) {
        reading.message = "no point of the stroke lies on screen: nothing read";
        timing_ = { clock.milliseconds(), 0 };
        return reading;
    }
    std::vector<Candidate> cloud;
    if (kind == MapperKind::Simple) {
        // 4.6.3: the current face's own contours instead of the training faces' cloud.
        if (!impl_->ownCurvature) {
            impl_->ownCurvature = std::make_unique<GpuCurvature>(impl_->device, model_.triangles, nv);
            impl_->ownCurvature->setPositions(meshMajorPositions({ currentFace }));
            impl_->ownCurvature->run();
            impl_->ownCloud.emplace(impl_->device, *impl_->ownCurvature, impl_->flags);
        } else {
            impl_->ownCurvature->setPositions(meshMajorPositions({ currentFace }));
            impl_->ownCurvature->run();
        }
        cloud = impl_->ownCloud->build(camera, contour);
    } else {
        cloud = impl_->cloud->build(camera, contour);
    }
    const std::vector<std::vector<int>> perPoint = candidatesPerPoint(
        cloud, camera, projected.screen, projected.world, radiusPx, params.depthToleranceMm, params.maxCandidatesPerPoint);
    std::size_t withCandidates = 0;
    for (std::size_t i = 0; i < n; ++i) {
        reading.candidateCounts[i] = static_cast<int>(perPoint[i].size());
        withCandidates += !perPoint[i].empty();
    }
    std::vector<Eigen::Vector2d> templateScreen(static_cast<std::size_t>(nv));
    for (Eigen::Index v = 0; v < nv; ++v) {
        const glm::dvec3 s = camera.project(glm::dvec3(currentFace.V(v, 0), currentFace.V(v, 1), currentFace.V(v, 2)));
        templateScreen[static_cast<std::size_t>(v)] = Eigen::Vector2d(s.x, s.y);
    }
    const double candidatesMs = clock.milliseconds();
    if (withCandidates == 0) {
        reading.message = cat("no contour candidate lies within ", radiusPx, " px of the stroke",
            projected.fellBackToPaper ? " (it misses the face)" : "", ": nothing read");
        timing_ = { candidatesMs, 0 };
        return reading;
    }

    const MappingProblem problem { camera, projected.screen, projected.world, cloud, perPoint, templateScreen, impl_->rings, tau, params };
    Mapping mapping;
    switch (kind) {
    case MapperKind::Nearest:
    case MapperKind::Simple:
        mapping = mapNearest(problem);
        break;
    case MapperKind::Heuristic:
        mapping = mapHeuristic(problem);
        break;
    case MapperKind::Hmm:
        mapping = mapHmm(problem);
        break;
    }
    reading.chosen = mapping.chosen;
    reading.observations = std::move(mapping.observations);
    if (withCandidates < n)
        reading.message
            = cat(n - withCandidates, " of ", n, " points have no contour candidate within ", radiusPx, " px and were not read");
    timing_ = { candidatesMs, clock.milliseconds() - candidatesMs };
    return reading;
}

} // namespace facesketch::sketch

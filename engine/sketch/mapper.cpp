#include "sketch/mapper.h"

#include "contours/candidates_gpu.h"
#include "contours/curvature_gpu.h"
#include "contours/region_candidates.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "geometry/graph.h"
#include "geometry/mesh_batch.h"
#include "geometry/wedges.h"
#include "sketch/mappers.h"
#include "sketch/projection.h"
#include "sketch/stroke_candidates.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

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

namespace {
constexpr int kRings = 4; // 4.8.4: k = 4
} // namespace

Eigen::Vector3d acrossStrokeAt(const std::vector<Eigen::Vector3d>& world, std::size_t i, const Eigen::Vector3d& axis)
{
    if (world.size() < 2 || i >= world.size())
        return Eigen::Vector3d::Zero();
    // The tangent over a few points either side: densified points a few pixels apart carry
    // the stroke's jitter in their direction.
    constexpr std::size_t kSpan = 2;
    const std::size_t a = i >= kSpan ? i - kSpan : 0, b = std::min(world.size() - 1, i + kSpan);
    Eigen::Vector3d t = world[b] - world[a];
    t -= axis * axis.dot(t);
    if (!t.allFinite() || t.norm() < 1e-9)
        return Eigen::Vector3d::Zero();
    return axis.cross(t.normalized()).normalized();
}

struct StrokeReader::Impl {
    Impl(gpu::Device& device, const stats::FaceModel& model, const std::vector<Mesh>& faces, std::vector<std::uint32_t> flagsIn)
        : flags(std::move(flagsIn))
        , curvature(device, model.triangles, model.vertexCount())
        , rings(model.triangles, model.vertexCount(), kRings)
        , device(device)
    {
        curvature.setPositions(meshMajorPositions(faces));
        facePositions.resize(static_cast<Eigen::Index>(faces.size()), 3 * model.vertexCount());
        for (std::size_t f = 0; f < faces.size(); ++f)
            for (Eigen::Index v = 0; v < model.vertexCount(); ++v)
                facePositions.row(static_cast<Eigen::Index>(f)).segment<3>(3 * v) = faces[f].V.row(v).cast<float>();
        curvature.run();
        cloud.emplace(device, curvature, flags);
        faceCount = static_cast<std::uint32_t>(faces.size());
        Mesh mean;
        mean.F = model.triangles;
        mean.V = asVertices(model.meanFace);
        featureSize = meanEdgeLength(mean);
        // Hops from the open border (edges of one triangle), up to kBorderScan rings.
        std::map<std::pair<int, int>, int> edgeUse;
        for (Eigen::Index t = 0; t < model.triangles.rows(); ++t)
            for (int c = 0; c < 3; ++c) {
                const int a = model.triangles(t, c), b = model.triangles(t, (c + 1) % 3);
                ++edgeUse[{ std::min(a, b), std::max(a, b) }];
            }
        borderHops.assign(static_cast<std::size_t>(model.vertexCount()), kBorderScan);
        std::vector<std::uint32_t> frontier;
        for (const auto& [edge, uses] : edgeUse)
            if (uses == 1)
                for (int v : { edge.first, edge.second })
                    if (borderHops[static_cast<std::size_t>(v)] != 0) {
                        borderHops[static_cast<std::size_t>(v)] = 0;
                        frontier.push_back(static_cast<std::uint32_t>(v));
                    }
        const Neighbours oneRing = buildNeighbours(buildWedges(model.triangles, model.vertexCount()));
        for (int h = 1; h < kBorderScan && !frontier.empty(); ++h) {
            std::vector<std::uint32_t> next;
            for (std::uint32_t v : frontier)
                for (std::uint32_t e = oneRing.offsets[v]; e < oneRing.offsets[v + 1]; ++e)
                    if (borderHops[oneRing.vertices[e]] > h) {
                        borderHops[oneRing.vertices[e]] = h;
                        next.push_back(oneRing.vertices[e]);
                    }
            frontier.swap(next);
        }
    }
    static constexpr int kBorderScan = 16;
    std::vector<int> borderHops; // per vertex: rings from the open border (kBorderScan: further)

    std::vector<std::uint32_t> flags;
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> facePositions; // faces by 3#V
    GpuCurvature curvature;
    std::optional<GpuCandidates> cloud;
    RingDistances rings;
    gpu::Device& device;
    double featureSize = 1;
    std::uint32_t faceCount = 0;
    // The current face's own contours (the simple mapper's, MapperParams::ownContours): on
    // the CPU, from the curvature of the stroke box's region only (contours/region_candidates.h).
    std::optional<RegionCandidates> own;
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

StrokeReading StrokeReader::read(const Stroke& stroke, const Mesh& currentFace, MapperKind kind, const MapperParams& params,
    const ReadAnchor* anchor, const std::vector<char>* drawn)
{
    validateStroke(stroke, "stroke");
    params.validate();
    const Eigen::Index nv = model_.vertexCount();
    if (anchor) {
        if (anchor->rings < 0 || anchor->rings > impl_->rings.rings())
            fail("stroke: anchor rings ", anchor->rings, " not in [0, ", impl_->rings.rings(), "]");
        for (std::uint32_t v : anchor->vertices)
            if (v >= static_cast<std::uint64_t>(nv))
                fail("stroke: anchor vertex ", v, " outside the face's ", nv, " vertices");
    }
    if (drawn && drawn->size() != static_cast<std::size_t>(nv))
        fail("stroke: ", drawn->size(), " drawn-vertex flags for the model's ", nv, " vertices");
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
    const double ppmm = pixelsPerMm(camera, centre);
    const double tau = params.tauMm * ppmm;
    const double radiusPx = params.candidateRadiusTau * tau;

    ContourParams contour;
    contour.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    contour.featureSize = impl_->featureSize;
    if (params.rtscSuggestive) {
        contour.suggestiveFilter = SuggestiveFilter::RtscCrossing;
        contour.rtscThreshold = params.rtscThreshold;
    }
    if (!strokeBox(contour, camera, projected.screen, projected.world, radiusPx, std::hypot(radiusPx / ppmm, params.depthToleranceMm))) {
        reading.message = "no point of the stroke lies on screen: nothing read";
        timing_ = { clock.milliseconds(), 0 };
        return reading;
    }
    auto ownCandidates = [&] {
        if (!impl_->own)
            impl_->own.emplace(model_.triangles, nv, impl_->flags);
        std::vector<Candidate> own = impl_->own->build(currentFace, camera, contour);
        if (anchor)
            own.erase(std::remove_if(own.begin(), own.end(),
                          [&](const Candidate& c) {
                              if (c.types & ContourSilhouette)
                                  return false;
                              for (std::uint32_t a : anchor->vertices)
                                  if (const int h = impl_->rings.hops(a, c.vertex); h >= 0 && h <= anchor->rings)
                                      return false;
                              return true;
                          }),
                own.end());
        return own;
    };
    std::vector<Candidate> cloud;
    if (kind == MapperKind::Simple) {
        // 4.6.3: the current face's own contours instead of the training faces' cloud.
        cloud = ownCandidates();
    } else {
        cloud = impl_->cloud->build(camera, contour);
        if (params.ownContours)
            for (Candidate c : ownCandidates()) {
                c.mesh = impl_->faceCount;
                cloud.push_back(c);
            }
    }
    if (kind != MapperKind::Simple && params.similarFaces > 0 && params.similarFaces < static_cast<int>(impl_->faceCount)) {
        Eigen::RowVectorXf current(3 * nv);
        for (Eigen::Index v = 0; v < nv; ++v)
            current.segment<3>(3 * v) = currentFace.V.row(v).cast<float>();
        std::vector<std::pair<double, std::uint32_t>> distance(impl_->faceCount);
        for (std::uint32_t f = 0; f < impl_->faceCount; ++f)
            distance[f] = { static_cast<double>((impl_->facePositions.row(f) - current).squaredNorm()), f };
        std::partial_sort(distance.begin(), distance.begin() + params.similarFaces, distance.end());
        std::vector<bool> keep(impl_->faceCount + 1, false);
        keep[impl_->faceCount] = true; // the current face's own contours (ownContours)
        for (int k = 0; k < params.similarFaces; ++k)
            keep[distance[static_cast<std::size_t>(k)].second] = true;
        cloud.erase(std::remove_if(cloud.begin(), cloud.end(), [&](const Candidate& c) { return c.mesh >= keep.size() || !keep[c.mesh]; }),
            cloud.end());
    }
    if (params.borderRings > 0)
        cloud.erase(std::remove_if(cloud.begin(), cloud.end(),
                        [&](const Candidate& c) {
                            return !(c.types & ContourLabelled) && (c.types & ContourSilhouette)
                                && impl_->borderHops[c.vertex] < params.borderRings;
                        }),
            cloud.end());
    const std::vector<std::vector<int>> perPoint = candidatesPerPoint(
        cloud, camera, projected.screen, projected.world, radiusPx, params.depthToleranceMm, params.maxCandidatesPerPoint);
    std::size_t withCandidates = 0;
    for (std::size_t i = 0; i < n; ++i) {
        reading.candidateCounts[i] = static_cast<int>(perPoint[i].size());
        withCandidates += !perPoint[i].empty();
    }
    std::vector<Eigen::Vector2d> templateScreen(static_cast<std::size_t>(nv));
    std::vector<double> templateDepth(static_cast<std::size_t>(nv));
    const Eigen::Vector3d axis = viewAxis(camera);
    for (Eigen::Index v = 0; v < nv; ++v) {
        const glm::dvec3 s = camera.project(glm::dvec3(currentFace.V(v, 0), currentFace.V(v, 1), currentFace.V(v, 2)));
        templateScreen[static_cast<std::size_t>(v)] = Eigen::Vector2d(s.x, s.y);
        templateDepth[static_cast<std::size_t>(v)] = axis.dot(currentFace.V.row(v).transpose());
    }
    const double candidatesMs = clock.milliseconds();
    if (withCandidates == 0) {
        reading.message = cat("no contour candidate lies within ", radiusPx, " px of the stroke",
            projected.fellBackToPaper ? " (it misses the face)" : "", ": nothing read");
        timing_ = { candidatesMs, 0 };
        return reading;
    }

    const MappingProblem problem { camera, projected.screen, projected.world, cloud, perPoint, templateScreen, templateDepth, impl_->rings,
        tau, params, drawn };
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
    for (VertexObservation& o : reading.observations) {
        o.viewPlaneOnly = params.viewPlaneOnly;
        if (params.acrossStrokeOnly)
            o.acrossStroke = acrossStrokeAt(projected.world, static_cast<std::size_t>(o.strokePoint), axis);
    }
    if (withCandidates < n)
        reading.message
            = cat(n - withCandidates, " of ", n, " points have no contour candidate within ", radiusPx, " px and were not read");
    timing_ = { candidatesMs, clock.milliseconds() - candidatesMs };
    return reading;
}

} // namespace facesketch::sketch

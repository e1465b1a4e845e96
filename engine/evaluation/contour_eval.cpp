#include "evaluation/contour_eval.h"

#include "contours/candidates_gpu.h"
#include "contours/curvature.h"
#include "contours/curvature_gpu.h"
#include "core/error.h"
#include "geometry/grid_index.h"
#include "geometry/mesh_batch.h"
#include "sketch/mappers.h"
#include "sketch/stroke_candidates.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facesketch::evaluation {

const char* mappingName(ContourMapping mapping)
{
    switch (mapping) {
    case ContourMapping::KnownVertex:
        return "known-vertex";
    case ContourMapping::NearestCandidate:
        return "nearest-candidate";
    default:
        return "2d";
    }
}

namespace {

// Per-vertex distances between two 3#V vectors: (mean, max, all).
std::pair<double, double> errors(const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::VectorXd* perVertex)
{
    const Eigen::Index n = a.size() / 3;
    Eigen::VectorXd e(n);
    for (Eigen::Index v = 0; v < n; ++v)
        e[v] = (a.segment<3>(3 * v) - b.segment<3>(3 * v)).norm();
    if (perVertex)
        *perVertex = e;
    return { e.mean(), e.maxCoeff() };
}

} // namespace

std::vector<std::uint32_t> skinContourFlags(const dataset::Manifest& manifest)
{
    const dataset::Component* skin = manifest.component("skin");
    if (!skin)
        fail("skinContourFlags: the manifest has no skin component");
    std::vector<std::uint32_t> flags(skin->size(), 0);
    auto mark = [&](int v, std::uint32_t flag) {
        if (skin->contains(v))
            flags[v - skin->begin] |= flag;
    };
    for (const auto& [name, path] : manifest.contours)
        for (int v : path)
            mark(v, VertexLabelled);
    for (int v : manifest.excluded)
        mark(v, VertexExcluded);
    return flags;
}

std::vector<ContourEvalResult> evaluateContours(gpu::Device& device, const ContourEvalData& data, const ContourEvalOptions& options)
{
    if (!data.model)
        fail("evaluateContours: no model");
    const stats::FaceModel& model = *data.model;
    const Eigen::Index nv = model.vertexCount();
    auto checkMesh = [&](const Mesh& m, const std::string& what) {
        if (m.V.rows() != nv || m.F.rows() != model.triangles.rows())
            fail("evaluateContours: ", what, " has ", m.V.rows(), " vertices and ", m.F.rows(), " triangles; the model has ", nv, " and ",
                model.triangles.rows());
    };
    if (data.candidateFaces.empty() || data.testFaces.empty() || data.testNames.size() != data.testFaces.size())
        fail("evaluateContours: need candidate faces and named test faces");
    for (size_t i = 0; i < data.candidateFaces.size(); ++i)
        checkMesh(data.candidateFaces[i], cat("candidate face ", i));
    for (size_t i = 0; i < data.testFaces.size(); ++i)
        checkMesh(data.testFaces[i], data.testNames[i]);

    Mesh mean;
    mean.F = model.triangles;
    mean.V = asVertices(model.meanFace);
    ContourParams params;
    params.silhouetteThreshold = defaultSilhouetteThreshold(nv);
    params.suggestiveThreshold = options.suggestiveThreshold;
    params.featureSize = meanEdgeLength(mean);

    GpuCurvature curvature(device, model.triangles, nv);
    curvature.setPositions(meshMajorPositions(data.candidateFaces));
    curvature.run();
    GpuCandidates cloudBuilder(device, curvature, data.flags);

    std::vector<Curvature> testCurvature;
    for (const Mesh& face : data.testFaces)
        testCurvature.push_back(estimateCurvature(face));

    std::vector<ContourEvalResult> results;
    for (const auto& [viewName, angles] : options.views) {
        const Camera camera = frameMesh(mean, angles, options.imageSize, options.imageSize);
        const std::vector<Candidate> cloud = cloudBuilder.build(camera, params);
        const GridIndex index(sketch::screenPositions(cloud), 8.0);
        // Rows of the view's rotation: a point's 2D position in the view plane, in mm.
        const Eigen::Matrix<double, 2, 3> P = sketch::viewPlaneRows(camera);

        for (size_t f = 0; f < data.testFaces.size(); ++f) {
            const Mesh& face = data.testFaces[f];
            const Eigen::VectorXd truth = asVector(face.V);
            const std::vector<Candidate> points = contourCandidates({ face }, { testCurvature[f] }, data.flags, camera, params);
            const auto [meanFaceMean, meanFaceMax] = errors(model.meanFace, truth, nullptr);

            for (ContourMapping mapping : { ContourMapping::KnownVertex, ContourMapping::NearestCandidate, ContourMapping::Projected2D }) {
                // `own`: candidates of the current reconstruction (empty at first).
                auto rebuild = [&](const std::vector<Candidate>& own) {
                    // The nearest mapper's rule (sketch/mappers.h): each point to the nearest of
                    // the reconstruction's own candidates or the cloud's (own wins a tie), moved
                    // onto the point in the view plane with the candidate's depth (a point's own
                    // depth would pin a wrong vertex's depth); points per vertex averaged.
                    const GridIndex ownIndex(sketch::screenPositions(own), 8.0);
                    const std::vector<sketch::IndexedCandidates> lists = { { &own, &ownIndex }, { &cloud, &index } };
                    std::vector<sketch::VertexObservation> matches;
                    for (const Candidate& p : points) {
                        sketch::VertexObservation o;
                        o.vertex = p.vertex;
                        o.position = Eigen::Vector3d(p.world[0], p.world[1], p.world[2]);
                        if (mapping != ContourMapping::KnownVertex) {
                            const Eigen::Vector2d at(p.screen[0], p.screen[1]);
                            const auto [list, i] = sketch::nearestCandidate(lists, at);
                            if (list < 0)
                                continue;
                            const Candidate& match = (*lists[static_cast<std::size_t>(list)].candidates)[static_cast<std::size_t>(i)];
                            o.vertex = match.vertex;
                            o.position = sketch::adaptToStroke(camera, at, o.position, match);
                        }
                        matches.push_back(o);
                    }
                    // Solve, then drop the observations the face disagrees with most (a point
                    // mapped to the wrong vertex) and solve again: `trim` times.
                    std::vector<std::pair<Eigen::Index, Eigen::Vector3d>> kept;
                    for (const sketch::VertexObservation& o : sketch::averagePerVertex(matches))
                        kept.push_back({ static_cast<Eigen::Index>(o.vertex), o.position });
                    auto solve = [&] {
                        stats::Observations obs;
                        for (const auto& [vertex, xyz] : kept) {
                            if (mapping == ContourMapping::Projected2D)
                                obs.addProjectedVertex(vertex, P, P * xyz);
                            else
                                obs.addVertex(vertex, xyz);
                        }
                        return stats::reconstruct(model, obs, options.reconstruct);
                    };
                    stats::Reconstruction solved = solve();
                    for (int t = 0; mapping != ContourMapping::KnownVertex && t < options.trim && kept.size() > 8; ++t) {
                        std::vector<double> residual;
                        for (const auto& [vertex, xyz] : kept) {
                            const Eigen::Vector3d d = solved.face.segment<3>(3 * vertex) - xyz;
                            residual.push_back(mapping == ContourMapping::Projected2D ? (P * d).norm() : d.norm());
                        }
                        std::vector<double> sorted = residual;
                        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
                        const double bar = std::max(options.trimFactor * sorted[sorted.size() / 2], options.trimFloor);
                        std::vector<std::pair<Eigen::Index, Eigen::Vector3d>> next;
                        for (size_t i = 0; i < kept.size(); ++i)
                            if (residual[i] <= bar)
                                next.push_back(kept[i]);
                        if (next.size() == kept.size())
                            break;
                        kept = std::move(next);
                        solved = solve();
                    }
                    return std::make_pair(solved, static_cast<int>(kept.size()));
                };
                auto [r, observedCount] = rebuild({});
                for (int k = 0; mapping != ContourMapping::KnownVertex && k < options.refinements; ++k) {
                    Mesh current;
                    current.F = model.triangles;
                    current.V = asVertices(r.face);
                    const std::vector<Candidate> own
                        = contourCandidates({ current }, { estimateCurvature(current) }, data.flags, camera, params);
                    std::tie(r, observedCount) = rebuild(own);
                }
                ContourEvalResult result;
                result.face = data.testNames[f];
                result.view = viewName;
                result.mapping = mapping;
                result.points = static_cast<int>(points.size());
                result.observedVertices = observedCount;
                std::tie(result.meanError, result.maxError) = errors(r.face, truth, &result.vertexError);
                result.meanFaceMean = meanFaceMean;
                result.meanFaceMax = meanFaceMax;
                result.reconstruction.F = model.triangles;
                result.reconstruction.V = asVertices(r.face);
                results.push_back(std::move(result));
            }
        }
    }
    return results;
}

} // namespace facesketch::evaluation

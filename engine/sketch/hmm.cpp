// The HMM mapper (thesis 4.8): states are a point's candidates, Viterbi in log space over the
// points that have candidates (sketch/viterbi.h), O(n m^2).
#include "core/error.h"
#include "sketch/mappers.h"
#include "sketch/stroke_candidates.h"
#include "sketch/viterbi.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace facesketch::sketch {

Mapping mapHmm(const MappingProblem& problem)
{
    const MapperParams& params = problem.params;
    const std::size_t n = problem.screen.size();
    Mapping out;
    out.chosen.assign(n, -1);
    std::vector<std::size_t> points; // the trellis' layers: points with candidates, in order
    for (std::size_t i = 0; i < n; ++i)
        if (!problem.perPoint[i].empty())
            points.push_back(i);
    if (points.empty())
        return out;

    const double sigmaD = params.sigmaDTau * problem.tau;
    const double sigmaSkel = params.sigmaSkelTau * problem.tau;
    const double sigmaDrawn = params.drawnSigmaTau * problem.tau;
    const std::vector<char>* drawn = sigmaDrawn > 0 ? problem.drawn : nullptr;
    const Eigen::Vector3d axis = viewAxis(problem.camera);
    const double ppmm = pixelsPerMm(problem.camera, problem.world[points[0]]);
    auto candidate = [&](std::size_t point, Eigen::Index j) -> const Candidate& {
        return problem.cloud[static_cast<std::size_t>(problem.perPoint[point][static_cast<std::size_t>(j)])];
    };
    auto screenOf = [](const Candidate& c) { return Eigen::Vector2d(c.screen[0], c.screen[1]); };
    auto square = [](double x) { return x * x; };

    // Initial (4.45).
    const EndpointTerms ends = endpointTerms(problem, points, true);
    Eigen::VectorXd logInitial(static_cast<Eigen::Index>(ends.sx.size()));
    for (std::size_t j = 0; j < ends.sx.size(); ++j)
        logInitial[static_cast<Eigen::Index>(j)] = -0.5 * square(ends.sx[j] / params.sigmaS) - 0.5 * square(ends.sy[j] / params.sigmaS);

    // Emission (4.46, 4.47).
    std::vector<Eigen::VectorXd> logEmission(points.size());
    for (std::size_t l = 0; l < points.size(); ++l) {
        const std::size_t i = points[l];
        const Eigen::Index m = static_cast<Eigen::Index>(problem.perPoint[i].size());
        logEmission[l].resize(m);
        for (Eigen::Index j = 0; j < m; ++j) {
            const Candidate& c = candidate(i, j);
            logEmission[l][j] = -0.5 * square((screenOf(c) - problem.screen[i]).norm() / sigmaD);
            if (drawn && (*drawn)[c.vertex])
                logEmission[l][j] -= 0.5 * square((problem.templateScreen[c.vertex] - problem.screen[i]).norm() / sigmaDrawn);
        }
    }

    // 4.8.5.3: "the nearest stroke point is assigned to each contour", and psi_stroke compares
    // the candidates' displacement with that of their nearest stroke points (not with the step
    // between the two layers' points: with a stroke sampled more densely than the vertices,
    // consecutive points mostly share a vertex, and the step would punish every move to the
    // next vertex).
    std::vector<int> nearestPoint(problem.cloud.size(), -1);
    {
        const GridIndex strokeIndex(problem.screen, std::max(params.densifyGapPx, 1.0));
        for (std::size_t i : points)
            for (int c : problem.perPoint[i])
                if (nearestPoint[static_cast<std::size_t>(c)] < 0)
                    nearestPoint[static_cast<std::size_t>(c)] = strokeIndex.nearest(screenOf(problem.cloud[static_cast<std::size_t>(c)]));
    }

    // Per layer, what the transitions read of each state, gathered once as plain arrays (the
    // transition's inner loop runs m^2 times per layer and streams them): its screen position,
    // depth (pixels), template vertex on screen, nearest stroke point, and its vertex among the
    // layer's distinct vertices (a point's candidates are a few vertices from many faces, so
    // the ring map is looked up per pair of distinct vertices, not per pair of states).
    struct Layer {
        std::vector<double> x, y, templX, templY, strokeX, strokeY, depth, templDepth;
        std::vector<char> labelled;          // the candidate lies on a labelled line
        std::vector<int> local;              // index into vertices
        std::vector<std::uint32_t> vertices; // distinct, in order of first use
    };
    auto layerOf = [&](std::size_t point) {
        Layer L;
        std::map<std::uint32_t, int> seen;
        for (const int c : problem.perPoint[point]) {
            const Candidate& k = problem.cloud[static_cast<std::size_t>(c)];
            const Eigen::Vector2d& templ = problem.templateScreen[k.vertex];
            const Eigen::Vector2d& stroke = problem.screen[static_cast<std::size_t>(nearestPoint[static_cast<std::size_t>(c)])];
            L.x.push_back(k.screen[0]);
            L.y.push_back(k.screen[1]);
            L.templX.push_back(templ.x());
            L.templY.push_back(templ.y());
            L.strokeX.push_back(stroke.x());
            L.strokeY.push_back(stroke.y());
            L.depth.push_back(axis.dot(Eigen::Vector3d(k.world[0], k.world[1], k.world[2])) * ppmm);
            L.templDepth.push_back(problem.templateDepth[k.vertex] * ppmm);
            L.labelled.push_back((k.types & ContourLabelled) != 0);
            const auto [it, inserted] = seen.try_emplace(k.vertex, static_cast<int>(L.vertices.size()));
            if (inserted)
                L.vertices.push_back(k.vertex);
            L.local.push_back(it->second);
        }
        return L;
    };
    Layer previous = layerOf(points[0]);
    Eigen::MatrixXd hopCost, hopFrom;

    // Transition (4.48-4.53), one layer at a time (viterbi() asks for layers in order). Column
    // by column: a column of logT is contiguous, and its entries read the previous layer's
    // arrays in order.
    auto transition = [&](std::size_t l, Eigen::MatrixXd& logT) {
        Layer next = layerOf(points[l]);
        const Layer& a = previous;
        const Eigen::Index rows = logT.rows();
        if (params.useConnectivity) {
            hopCost.resize(static_cast<Eigen::Index>(a.vertices.size()), static_cast<Eigen::Index>(next.vertices.size()));
            for (std::size_t u = 0; u < a.vertices.size(); ++u)
                for (std::size_t w = 0; w < next.vertices.size(); ++w) {
                    const int hops = problem.rings.hops(a.vertices[u], next.vertices[w]);
                    const double psiC = hops < 0 ? params.unreachableHops : hops;
                    hopCost(static_cast<Eigen::Index>(u), static_cast<Eigen::Index>(w)) = -0.5 * square(psiC / params.sigmaC);
                }
            // From each previous state (not vertex) to each next vertex.
            hopFrom.resize(rows, hopCost.cols());
            for (Eigen::Index j = 0; j < rows; ++j)
                hopFrom.row(j) = hopCost.row(a.local[static_cast<std::size_t>(j)]);
        }
        // Locals, not params' fields: the stores to logT could alias them, so the compiler would
        // load them again for every entry.
        const bool useStroke = params.useStroke, useSkeleton = params.useSkeleton, depthFromFace = params.strokeDepthFromFace;
        const double sigmaStroke = params.sigmaStroke, minStep = params.densifyGapPx, skeletonSigma = sigmaSkel;
        for (Eigen::Index q = 0; q < logT.cols(); ++q) {
            const std::size_t sq = static_cast<std::size_t>(q);
            const double nx = next.x[sq], ny = next.y[sq], ntx = next.templX[sq], nty = next.templY[sq];
            const double npx = next.strokeX[sq], npy = next.strokeY[sq], nd = next.depth[sq], ntd = next.templDepth[sq];
            const bool nl = next.labelled[sq] != 0;
            const double* hop = params.useConnectivity ? hopFrom.col(next.local[sq]).data() : nullptr;
            double* out = logT.col(q).data();
            for (Eigen::Index j = 0; j < rows; ++j) {
                const std::size_t sj = static_cast<std::size_t>(j);
                double logP = 0;
                if (hop != nullptr)
                    logP += hop[j];
                const double dx = nx - a.x[sj], dy = ny - a.y[sj];
                if (useStroke) {
                    // c' = screen xy and the depth along the view axis, both in pixels; along a
                    // labelled line, the depth the current face's line turns through is not
                    // charged (MapperParams::strokeDepthFromFace).
                    double dz = nd - a.depth[sj];
                    if (depthFromFace && nl && a.labelled[sj] != 0)
                        dz -= ntd - a.templDepth[sj];
                    const double moved = std::sqrt(dx * dx + dy * dy + dz * dz);
                    const double sx = npx - a.strokeX[sj], sy = npy - a.strokeY[sj];
                    const double step = std::sqrt(sx * sx + sy * sy);
                    // The ratio of 4.49, its denominator at least the stroke's sampling step
                    // (finer displacements are not resolved; two candidates sharing their
                    // nearest point would divide by zero).
                    const double psiStroke = (moved - step) / std::max(step, minStep);
                    logP -= 0.5 * square(psiStroke / sigmaStroke);
                }
                if (useSkeleton) {
                    const double ex = dx - (ntx - a.templX[sj]), ey = dy - (nty - a.templY[sj]);
                    const double psiSkel = std::sqrt(ex * ex + ey * ey);
                    logP -= 0.5 * square(psiSkel / skeletonSigma);
                }
                out[j] = logP;
            }
        }
        previous = std::move(next);
    };
    const ViterbiPath path = viterbi(logInitial, logEmission, transition);

    // 4.8.2: several points on one vertex keep the closest (the highest emission).
    std::map<std::uint32_t, std::pair<double, std::size_t>> closest;
    for (std::size_t l = 0; l < points.size(); ++l) {
        const std::size_t i = points[l];
        const int c = problem.perPoint[i][static_cast<std::size_t>(path.states[l])];
        out.chosen[i] = c;
        const Candidate& k = problem.cloud[static_cast<std::size_t>(c)];
        const double d = (screenOf(k) - problem.screen[i]).norm();
        auto [slot, inserted] = closest.try_emplace(k.vertex, d, i);
        if (!inserted && d < slot->second.first)
            slot->second = { d, i };
    }
    for (const auto& [vertex, best] : closest) {
        const std::size_t i = best.second;
        VertexObservation o;
        o.vertex = vertex;
        o.position
            = adaptToStroke(problem.camera, problem.screen[i], problem.world[i], problem.cloud[static_cast<std::size_t>(out.chosen[i])]);
        o.strokePoint = static_cast<int>(i);
        out.observations.push_back(o);
    }
    std::sort(out.observations.begin(), out.observations.end(),
        [](const VertexObservation& a, const VertexObservation& b) { return a.strokePoint < b.strokePoint; });
    return out;
}

} // namespace facesketch::sketch

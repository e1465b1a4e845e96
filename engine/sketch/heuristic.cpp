// The heuristic mapper (thesis 4.6.1-4.6.2) and the endpoint metrics it shares with the HMM's
// initial probability (4.8.5.1).
#include "sketch/mappers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace facesketch::sketch {

EndpointTerms endpointTerms(const MappingProblem& problem, const std::vector<std::size_t>& points, bool first)
{
    EndpointTerms out;
    if (points.empty())
        return out;
    const std::size_t end = first ? points.front() : points.back();
    // Orientation (4.31's chart): the vector from the first point to the middle one.
    const Eigen::Vector2d direction = problem.screen[points[(points.size() - 1) / 2]] - problem.screen[points.front()];
    const bool omegaX = direction.x() < 0; // drawn right to left
    const bool omegaY = direction.y() < 0; // drawn bottom up (screen y grows downwards)
    // r_x, r_y (4.34, 4.35) from the stroke's box, blended linearly.
    Eigen::Vector2d lo = problem.screen[points.front()], hi = lo;
    for (std::size_t i : points) {
        lo = lo.cwiseMin(problem.screen[i]);
        hi = hi.cwiseMax(problem.screen[i]);
    }
    const double dx = hi.x() - lo.x(), dy = hi.y() - lo.y();
    const double rx = dx + dy > 0 ? dx / (dx + dy) : 0.5, ry = 1.0 - rx;

    const std::vector<int>& set = problem.perPoint[end];
    Eigen::Vector2d tlo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), thi = -tlo;
    for (int c : set) {
        const Eigen::Vector2d& t = problem.templateScreen[problem.cloud[static_cast<std::size_t>(c)].vertex];
        tlo = tlo.cwiseMin(t);
        thi = thi.cwiseMax(t);
    }
    for (int c : set) {
        const Eigen::Vector2d& t = problem.templateScreen[problem.cloud[static_cast<std::size_t>(c)].vertex];
        double phiX = thi.x() > tlo.x() ? (t.x() - tlo.x()) / (thi.x() - tlo.x()) : 0.0;
        double phiY = thi.y() > tlo.y() ? (t.y() - tlo.y()) / (thi.y() - tlo.y()) : 0.0;
        // 4.32, 4.33: the first point belongs at the edge the stroke starts from, the last at
        // the opposite one.
        if (first == omegaX)
            phiX = 1.0 - phiX;
        if (first == omegaY)
            phiY = 1.0 - phiY;
        out.sx.push_back(rx * phiX);
        out.sy.push_back(ry * phiY);
    }
    return out;
}

Mapping mapHeuristic(const MappingProblem& problem)
{
    const MapperParams& params = problem.params;
    const std::size_t n = problem.screen.size();
    Mapping out;
    out.chosen.assign(n, -1);
    std::vector<std::size_t> points;
    for (std::size_t i = 0; i < n; ++i)
        if (!problem.perPoint[i].empty())
            points.push_back(i);
    if (points.empty())
        return out;

    // The stroke's extreme points (condition 1): start, end, top, bottom, left, right.
    std::vector<char> extreme(n, 0);
    {
        std::size_t top = points[0], bottom = top, left = top, right = top;
        for (std::size_t i : points) {
            const Eigen::Vector2d& p = problem.screen[i];
            top = p.y() < problem.screen[top].y() ? i : top;
            bottom = p.y() > problem.screen[bottom].y() ? i : bottom;
            left = p.x() < problem.screen[left].x() ? i : left;
            right = p.x() > problem.screen[right].x() ? i : right;
        }
        for (std::size_t i : { points.front(), points.back(), top, bottom, left, right })
            extreme[i] = 1;
    }
    const EndpointTerms firstTerms = endpointTerms(problem, points, true);
    const EndpointTerms lastTerms = endpointTerms(problem, points, false);
    const double lambdaPx = params.lambda * problem.tau;
    const double endpointRadiusPx = params.heuristicEndpointRadiusTau * problem.tau;
    auto screenOf = [](const Candidate& c) { return Eigen::Vector2d(c.screen[0], c.screen[1]); };

    struct Assigned {
        std::size_t point;
        int candidate;
        double grade; // an error: lower is better
    };
    std::map<std::uint32_t, Assigned> byVertex;
    std::size_t lastPoint = 0;
    int lastCandidate = -1;
    for (std::size_t l = 0; l < points.size(); ++l) {
        const std::size_t i = points[l];
        const std::vector<int>& set = problem.perPoint[i];
        const bool isFirst = l == 0, isLast = l + 1 == points.size();
        double bestGrade = std::numeric_limits<double>::infinity();
        int best = -1;
        for (std::size_t j = 0; j < set.size(); ++j) {
            const Candidate& c = problem.cloud[static_cast<std::size_t>(set[j])];
            double grade = 0;
            // psi: the endpoint term on the first and last point only (4.29), among the
            // candidates near the end point (the set is nearest first).
            if ((isFirst || isLast) && j > 0 && (screenOf(c) - problem.screen[i]).norm() > endpointRadiusPx)
                continue;
            if (isFirst)
                grade += lambdaPx * (firstTerms.sx[j] + firstTerms.sy[j]);
            else if (isLast)
                grade += lambdaPx * (lastTerms.sx[j] + lastTerms.sy[j]);
            if (lastCandidate >= 0) {
                const Candidate& previous = problem.cloud[static_cast<std::size_t>(lastCandidate)];
                const Eigen::Vector2d stroke = problem.screen[i] - problem.screen[lastPoint];
                const double s1 = (stroke - (screenOf(c) - screenOf(previous))).norm();                                           // 4.36
                const double s2 = (stroke - (problem.templateScreen[c.vertex] - problem.templateScreen[previous.vertex])).norm(); // 4.37
                grade += params.alpha * s1 + params.beta * s2;
                if (params.heuristicConnectivity) {
                    const int hops = problem.rings.hops(previous.vertex, c.vertex);
                    grade *= 1.0 + (hops < 0 ? params.unreachableHops : hops);
                }
            } else if (!isFirst) {
                // No point assigned yet (the first one lost its vertex): the nearest wins.
                grade += (screenOf(c) - problem.screen[i]).norm();
            }
            if (grade < bestGrade) {
                bestGrade = grade;
                best = set[j];
            }
        }
        const Candidate& chosen = problem.cloud[static_cast<std::size_t>(best)];
        auto it = byVertex.find(chosen.vertex);
        if (it != byVertex.end()) {
            // Condition 1: an extreme point's vertex stays; condition 2: a better grade takes over.
            if (extreme[it->second.point] || (!extreme[i] && bestGrade >= it->second.grade))
                continue;
            out.chosen[it->second.point] = -1;
            it->second = { i, best, bestGrade };
        } else {
            byVertex.emplace(chosen.vertex, Assigned { i, best, bestGrade });
        }
        out.chosen[i] = best;
        lastPoint = i;
        lastCandidate = best;
    }
    for (const auto& [vertex, a] : byVertex) {
        VertexObservation o;
        o.vertex = vertex;
        o.position = adaptToStroke(
            problem.camera, problem.screen[a.point], problem.world[a.point], problem.cloud[static_cast<std::size_t>(a.candidate)]);
        o.strokePoint = static_cast<int>(a.point);
        out.observations.push_back(o);
    }
    std::sort(out.observations.begin(), out.observations.end(),
        [](const VertexObservation& a, const VertexObservation& b) { return a.strokePoint < b.strokePoint; });
    return out;
}

} // namespace facesketch::sketch

// The nearest mapper (the baseline of sketch/mapper.h) and the mapping pieces it shares with
// evaluation/contour_eval.cpp.
#include "sketch/mappers.h"
#include "sketch/projection.h"
#include "sketch/stroke_candidates.h"

#include <algorithm>
#include <map>

namespace facesketch::sketch {

Eigen::Vector3d adaptToStroke(const Camera& camera, const Eigen::Vector2d& screen, const Eigen::Vector3d& world, const Candidate& candidate)
{
    const Eigen::Vector3d c(candidate.world[0], candidate.world[1], candidate.world[2]);
    if (camera.kind == Projection::Orthographic) {
        const Eigen::Matrix<double, 2, 3> P = viewPlaneRows(camera);
        const Eigen::Vector3d depthAxis = viewAxis(camera);
        return P.transpose() * (P * world) + depthAxis * depthAxis.dot(c);
    }
    const glm::dvec3 s = camera.project(glm::dvec3(c.x(), c.y(), c.z()));
    return unproject(camera, screen.x(), screen.y(), s.z);
}

std::vector<VertexObservation> averagePerVertex(const std::vector<VertexObservation>& observations)
{
    // Eigen vectors do not zero themselves: each sum starts explicitly.
    std::map<std::uint32_t, std::pair<VertexObservation, int>> sums;
    for (const VertexObservation& o : observations) {
        auto [slot, inserted] = sums.try_emplace(o.vertex, o, 0);
        if (inserted)
            slot->second.first.position = Eigen::Vector3d::Zero();
        slot->second.first.position += o.position;
        slot->second.second += 1;
    }
    std::vector<VertexObservation> out;
    for (auto& [vertex, sum] : sums) {
        sum.first.position = sum.first.position / sum.second;
        out.push_back(sum.first);
    }
    return out;
}

std::pair<int, int> nearestCandidate(const std::vector<IndexedCandidates>& lists, const Eigen::Vector2d& q)
{
    std::pair<int, int> best { -1, -1 };
    double bestD2 = 0;
    for (std::size_t l = 0; l < lists.size(); ++l) {
        const int i = lists[l].index->nearest(q);
        if (i < 0)
            continue;
        const Candidate& c = (*lists[l].candidates)[static_cast<std::size_t>(i)];
        const double d2 = std::pow(c.screen[0] - q.x(), 2) + std::pow(c.screen[1] - q.y(), 2);
        if (best.first < 0 || d2 < bestD2) {
            best = { static_cast<int>(l), i };
            bestD2 = d2;
        }
    }
    return best;
}

std::vector<Eigen::Vector2d> screenPositions(const std::vector<Candidate>& candidates)
{
    std::vector<Eigen::Vector2d> out(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i)
        out[i] = Eigen::Vector2d(candidates[i].screen[0], candidates[i].screen[1]);
    return out;
}

Mapping mapNearest(const MappingProblem& problem)
{
    Mapping out;
    const std::size_t n = problem.screen.size();
    out.chosen.assign(n, -1);
    std::vector<VertexObservation> matches;
    for (std::size_t i = 0; i < n; ++i) {
        if (problem.perPoint[i].empty())
            continue;
        const int c = problem.perPoint[i].front();
        out.chosen[i] = c;
        const Candidate& candidate = problem.cloud[static_cast<std::size_t>(c)];
        VertexObservation o;
        o.vertex = candidate.vertex;
        o.position = adaptToStroke(problem.camera, problem.screen[i], problem.world[i], candidate);
        o.strokePoint = static_cast<int>(i);
        matches.push_back(o);
    }
    out.observations = averagePerVertex(matches);
    std::stable_sort(out.observations.begin(), out.observations.end(),
        [](const VertexObservation& a, const VertexObservation& b) { return a.strokePoint < b.strokePoint; });
    return out;
}

} // namespace facesketch::sketch

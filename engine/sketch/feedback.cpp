#include "sketch/feedback.h"

#include "core/error.h"

#include <algorithm>
#include <numeric>

namespace facesketch::sketch {

InterpretedStroke interpretStroke(const StrokeReading& reading, const Mesh& face, const Camera& camera)
{
    std::vector<VertexObservation> order = reading.observations;
    for (const VertexObservation& o : order)
        if (o.vertex >= static_cast<std::uint64_t>(face.V.rows()))
            fail("interpretStroke: vertex ", o.vertex, " outside the face's ", face.V.rows(), " vertices");
    std::stable_sort(order.begin(), order.end(), [](const VertexObservation& a, const VertexObservation& b) {
        return a.strokePoint != b.strokePoint ? a.strokePoint < b.strokePoint : a.vertex < b.vertex;
    });
    InterpretedStroke out;
    for (const VertexObservation& o : order) {
        const Eigen::Vector3d x = face.V.row(o.vertex).transpose();
        const glm::dvec3 s = camera.project(glm::dvec3(x.x(), x.y(), x.z()));
        out.vertices.push_back(o.vertex);
        out.world.push_back(x);
        out.screen.push_back({ s.x, s.y });
    }
    return out;
}

std::vector<std::pair<int, double>> mostSimilarFaces(const Mesh& face, std::span<const Mesh> faces, int k)
{
    std::vector<std::pair<int, double>> all;
    for (size_t i = 0; i < faces.size(); ++i) {
        if (faces[i].V.rows() != face.V.rows())
            fail("mostSimilarFaces: face ", i, " has ", faces[i].V.rows(), " vertices, the query ", face.V.rows());
        all.push_back({ static_cast<int>(i), (faces[i].V - face.V).rowwise().norm().mean() });
    }
    std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
    all.resize(std::min(all.size(), static_cast<size_t>(std::max(0, k))));
    return all;
}

} // namespace facesketch::sketch

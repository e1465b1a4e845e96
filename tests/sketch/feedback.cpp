// What the user sees of a reading: the interpreted stroke and the most similar faces.
#include "sketch/feedback.h"

#include "core/error.h"

#include <catch2/catch.hpp>

using namespace facesketch;
using namespace facesketch::sketch;

namespace {

Mesh strip()
{
    Mesh m;
    m.V.resize(4, 3);
    m.V << 0, 0, 0, 10, 0, 0, 20, 0, 0, 30, 5, 0;
    m.F.resize(2, 3);
    m.F << 0, 1, 2, 1, 3, 2;
    return m;
}

} // namespace

TEST_CASE("feedback: the interpreted stroke follows the stroke order through the rebuilt face")
{
    const Mesh face = strip();
    StrokeReading r;
    for (auto [vertex, point] : { std::pair<std::uint32_t, int> { 3, 9 }, { 0, 1 }, { 2, 4 } }) {
        VertexObservation o;
        o.vertex = vertex;
        o.strokePoint = point;
        o.position = Eigen::Vector3d(99, 99, 99); // where the stroke put it; the face decides
        r.observations.push_back(o);
    }
    const Camera camera = frameSphere({ 15, 0, 0 }, 20, { 0, 0 }, 200, 100);
    const InterpretedStroke s = interpretStroke(r, face, camera);
    REQUIRE(s.vertices == std::vector<std::uint32_t> { 0, 2, 3 });
    REQUIRE(s.world[2] == Eigen::Vector3d(30, 5, 0));
    const glm::dvec3 p = camera.project({ 20, 0, 0 });
    REQUIRE(s.screen[1].x() == p.x);
    REQUIRE(s.screen[1].y() == p.y);
    REQUIRE(s.screen[0].x() < s.screen[1].x()); // x to the right from the front
    r.observations[0].vertex = 4;
    REQUIRE_THROWS_WITH(interpretStroke(r, face, camera), Catch::Contains("vertex 4 outside"));
}

TEST_CASE("feedback: the most similar faces come nearest first")
{
    const Mesh face = strip();
    std::vector<Mesh> faces(4, face);
    faces[0].V.array() += 3.0;
    faces[1].V.col(1).array() += 1.0;
    faces[2].V.col(2).array() -= 2.0;
    faces[3].V.array() += 0.0;
    const auto best = mostSimilarFaces(face, faces, 3);
    REQUIRE(best.size() == 3);
    REQUIRE(best[0] == std::pair<int, double> { 3, 0.0 });
    REQUIRE(best[1].first == 1);
    REQUIRE(best[1].second == Approx(1.0));
    REQUIRE(best[2].first == 2);
    REQUIRE(mostSimilarFaces(face, faces, 10).size() == 4);
    faces[1].V.conservativeResize(3, 3);
    REQUIRE_THROWS_WITH(mostSimilarFaces(face, faces, 2), Catch::Contains("face 1"));
}

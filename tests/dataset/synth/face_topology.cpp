// The shared structure of each resolution: sizes, components, slits and labels.
#include "dataset/synth/face_generator.h"
#include "test_common.h"

#include <map>
#include <set>

using namespace facesketch;
using namespace facesketch::dataset;

namespace {

// Undirected edge -> number of triangles using it, for triangles with a vertex in [begin, end).
std::map<std::pair<int, int>, int> edgeUse(const Triangles& F, int begin, int end)
{
    std::map<std::pair<int, int>, int> use;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        if (F(f, 0) < begin || F(f, 0) >= end)
            continue;
        for (int k = 0; k < 3; ++k)
            ++use[std::minmax(F(f, k), F(f, (k + 1) % 3))];
    }
    return use;
}

} // namespace

TEST_CASE("face_topology: about 900, 6,000 and 25,000 vertices, all labels valid")
{
    const std::map<Resolution, std::pair<int, int>> expected
        = { { Resolution::Low, { 800, 1000 } }, { Resolution::High, { 5500, 6500 } }, { Resolution::Ultra, { 23000, 27000 } } };
    std::set<std::string> landmarkNames, contourNames;
    for (const auto& [r, range] : expected) {
        const FaceTopology t = buildFaceTopology(r);
        const Manifest& m = t.labels;
        INFO(resolutionName(r) << ": " << m.vertexCount << " vertices");
        REQUIRE(m.vertexCount >= range.first);
        REQUIRE(m.vertexCount <= range.second);
        REQUIRE_NOTHROW(validateManifest(m, "synthetic"));
        REQUIRE(m.components.size() == 6);
        REQUIRE(m.components.back().end == m.vertexCount);
        // 46 MPEG-4 points: 40 skin, 4 tongue, 2 lower teeth (thesis 5.2).
        int skin = 0, tongue = 0, teeth = 0;
        for (const auto& [name, v] : m.mpeg4) {
            skin += m.component("skin")->contains(v);
            tongue += m.component("tongue")->contains(v);
            teeth += m.component("teeth_lower")->contains(v);
        }
        REQUIRE(m.mpeg4.size() == 46);
        REQUIRE(skin == 40);
        REQUIRE(tongue == 4);
        REQUIRE(teeth == 2);
        // Every resolution shares the landmark and contour names.
        std::set<std::string> lm, ct;
        for (const auto& [name, v] : m.landmarks)
            lm.insert(name);
        for (const auto& [name, v] : m.contours)
            ct.insert(name);
        if (landmarkNames.empty()) {
            landmarkNames = lm;
            contourNames = ct;
        }
        REQUIRE(lm == landmarkNames);
        REQUIRE(ct == contourNames);
        // Same resolution, same topology.
        REQUIRE(buildFaceTopology(r).labels.topology == m.topology);
    }
    for (const char* name : { "prn", "ex_l", "ex_r", "en_l", "en_r", "al_l", "al_r", "ch_l", "ch_r", "sn", "sto", "pg", "gn", "n" })
        REQUIRE(landmarkNames.count(name));
    for (const char* name :
        { "eyebrow_l", "eyebrow_r", "lip_upper_outer", "lip_lower_outer", "nostril_l", "nostril_r", "eye_socket_l", "eye_socket_r" })
        REQUIRE(contourNames.count(name));
}

TEST_CASE("face_topology: eyeballs, teeth and tongue are closed, and the skin's holes are the eye sockets and mouth")
{
    const FaceTopology t = buildFaceTopology(Resolution::Low);
    const Manifest& m = t.labels;
    for (const Component& c : m.components) {
        const auto use = edgeUse(m.topology, c.begin, c.end);
        int boundary = 0;
        for (const auto& [edge, n] : use) {
            REQUIRE(n <= 2); // manifold
            boundary += n == 1;
            REQUIRE(c.contains(edge.first));
            REQUIRE(c.contains(edge.second));
        }
        INFO(c.name);
        if (c.name != "skin")
            REQUIRE(boundary == 0);
    }
    // Skin boundary edges: the outer rim plus the eye socket loops and the mouth loop.
    const auto use = edgeUse(m.topology, 0, m.component("skin")->end);
    auto isBoundary = [&](int a, int b) {
        auto it = use.find(std::minmax(a, b));
        return it != use.end() && it->second == 1;
    };
    for (const char* loop : { "eye_socket_l", "eye_socket_r" }) {
        const auto& path = m.contours.at(loop);
        for (size_t i = 0; i < path.size(); ++i) {
            INFO(loop << " edge " << i);
            REQUIRE(isBoundary(path[i], path[(i + 1) % path.size()]));
        }
    }
    for (const char* lip : { "lip_upper_inner", "lip_lower_inner" }) {
        const auto& path = m.contours.at(lip);
        for (size_t i = 0; i + 1 < path.size(); ++i) {
            INFO(lip << " edge " << i);
            REQUIRE(isBoundary(path[i], path[i + 1]));
        }
    }
    int boundaryEdges = 0;
    for (const auto& [edge, n] : use)
        boundaryEdges += n == 1;
    const int rim = 2 * (t.rows - 1) + 2 * (t.cols - 1);
    const int eyes = 2 * 2 * (t.sEx - t.sEn), mouth = 2 * 2 * t.sCh;
    REQUIRE(boundaryEdges == rim + eyes + mouth);
    // The exclusion list holds hidden vertices only: nostril pits and under the chin.
    REQUIRE(!m.excluded.empty());
    for (int v : m.excluded)
        REQUIRE(m.component("skin")->contains(v));
}

TEST_CASE("face_topology: parseResolution names the bad value")
{
    REQUIRE(parseResolution("ultra") == Resolution::Ultra);
    REQUIRE_THROWS_WITH(parseResolution("medium"), Catch::Contains("medium"));
}

// ICT Face Model Light import (import_ict.h).
//
// Sources: ICT-FaceKit (Li, Ruizhe et al., "Learning Formation of Physically-Based Face
// Attributes", CVPR 2020; https://github.com/ICT-VGL/ICT-FaceKit, README "Regions" for the
// vertex ranges and the 68 landmark indices); the 68-point Multi-PIE / iBUG 300-W landmark
// scheme (Sagonas et al., 300 Faces in-the-Wild Challenge, 2013); landmark definitions of
// thesis Table 3.1 (Farkas, Anthropometry of the Head and Face, 1994); Box-Muller (Box and
// Muller, 1958); SplitMix64 (Steele, Lea and Flood, 2014).
#include "dataset/import_ict.h"

#include "core/error.h"
#include "core/names.h"
#include "core/random.h"
#include "dataset/dataset.h"
#include "dataset/simplify.h"
#include "dataset/synth.h"
#include "io/mesh_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <set>
#include <sstream>
#include <string_view>

namespace facesketch::dataset {

namespace fs = std::filesystem;

namespace {

constexpr double kCmToMm = 10.0;
constexpr int kIctVertexCount = 26719;

// Vertex ranges of the full ICT mesh (ICT-FaceKit README), half-open.
struct Range {
    const char* name;
    int begin, end;
};
constexpr Range kEyeSocketLeft { "eye_socket_left", 13294, 13678 };
constexpr Range kEyeSocketRight { "eye_socket_right", 13678, 14062 };
constexpr Range kEyeLeft { "eye_left", 21451, 23021 };
constexpr Range kEyeRight { "eye_right", 23021, 24591 };
constexpr Range kMouthSocket { "mouth_socket", 11248, 13294 };
// ICT's "gums and tongue" range [14062, 17039) is one connected mesh; its last 428 vertices are
// the tongue body (open at the root, sewn to the floor of the mouth by 25 edges along the
// frenulum). See import_ict.h for how the split was found.
constexpr Range kGums { "gums", 14062, 16611 };
constexpr Range kTongue { "tongue", 16611, 17039 };
constexpr Range kTeethUpper { "teeth_upper", 17039, 19247 };
constexpr Range kTeethLower { "teeth_lower", 19247, 21451 };

// The 68 Multi-PIE landmarks as listed in ICT-FaceKit's README (used if vertex_indices.json is absent).
constexpr int kReadmeLandmarks[68] = { 1225, 1888, 1052, 367, 1719, 1722, 2199, 1447, 966, 3661, 4390, 3927, 3924, 2608, 3272, 4088, 3443,
    268, 493, 1914, 2044, 1401, 3615, 4240, 4114, 2734, 2509, 978, 4527, 4942, 4857, 1140, 2075, 1147, 4269, 3360, 1507, 1542, 1537, 1528,
    1518, 1511, 3742, 3751, 3756, 3721, 3725, 3732, 5708, 5695, 2081, 0, 4275, 6200, 6213, 6346, 6461, 5518, 5957, 5841, 5702, 5711, 5533,
    6216, 6207, 6470, 5517, 5966 };

fs::path modelFolder(const fs::path& path)
{
    if (fs::is_regular_file(path / "FaceXModel" / "generic_neutral_mesh.obj"))
        return path / "FaceXModel";
    if (fs::is_regular_file(path / "generic_neutral_mesh.obj"))
        return path;
    if (!fs::exists(path))
        fail(path.string(), ": does not exist");
    fail(path.string(), ": no FaceXModel/generic_neutral_mesh.obj (not an ICT-FaceKit folder)");
}

// The `v` lines of an OBJ file as #V by 3 (file units). Other statements are skipped.
Vertices readObjPositions(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path.string(), ": cannot open");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    std::vector<double> xyz;
    xyz.reserve(3 * kIctVertexCount);
    long line = 0;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos)
            end = text.size();
        ++line;
        const char* p = text.data() + pos;
        const char* e = text.data() + end;
        pos = end + 1;
        if (e - p < 2 || p[0] != 'v' || (p[1] != ' ' && p[1] != '\t'))
            continue;
        const std::string_view lineText(p, static_cast<size_t>(e - p));
        p += 2;
        for (int c = 0; c < 3; ++c) {
            while (p < e && (*p == ' ' || *p == '\t'))
                ++p;
            double value = 0;
            const auto [next, ec] = std::from_chars(p, e, value);
            if (ec != std::errc() || (next < e && *next != ' ' && *next != '\t' && *next != '\r'))
                fail(path.string(), ":", line, ": vertex coordinate ", "xyz"[c], " is missing or not a number: '", lineText, "'");
            if (!std::isfinite(value))
                fail(path.string(), ":", line, ": vertex coordinate ", "xyz"[c], " is ", value);
            xyz.push_back(value);
            p = next;
        }
    }
    Vertices V(static_cast<Eigen::Index>(xyz.size() / 3), 3);
    std::copy(xyz.begin(), xyz.end(), V.data());
    return V;
}

std::vector<int> readLandmarkIndices(const fs::path& folder)
{
    const fs::path file = folder / "vertex_indices.json";
    if (!fs::exists(file))
        return { std::begin(kReadmeLandmarks), std::end(kReadmeLandmarks) };
    std::ifstream in(file);
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        fail(file.string(), ": not valid JSON: ", e.what());
    }
    if (!doc.is_object() || !doc.contains("idx_to_landmark_verts") || !doc["idx_to_landmark_verts"].is_array())
        fail(file.string(), ": idx_to_landmark_verts: missing or not an array");
    const auto& list = doc["idx_to_landmark_verts"];
    if (list.size() != 68)
        fail(file.string(), ": idx_to_landmark_verts: has ", list.size(), " entries, expected the 68 Multi-PIE points");
    std::vector<int> out;
    for (size_t i = 0; i < list.size(); ++i) {
        if (!list[i].is_number_integer() || list[i].get<long>() < 0 || list[i].get<long>() >= kIctVertexCount)
            fail(file.string(), ": idx_to_landmark_verts[", i, "]: '", list[i].dump(), "' is not a vertex index below ", kIctVertexCount);
        out.push_back(list[i].get<int>());
    }
    return out;
}

// Adjacency of the skin (vertices [0, skinEnd)) with edge lengths.
using Graph = std::vector<std::vector<std::pair<int, double>>>;

Graph skinGraph(const Vertices& V, const Triangles& F, int skinEnd)
{
    std::vector<std::set<int>> nb(static_cast<size_t>(skinEnd));
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = F(f, k), b = F(f, (k + 1) % 3);
            if (a < skinEnd && b < skinEnd) {
                nb[static_cast<size_t>(a)].insert(b);
                nb[static_cast<size_t>(b)].insert(a);
            }
        }
    Graph g(nb.size());
    for (size_t a = 0; a < nb.size(); ++a)
        for (int b : nb[a])
            g[a].push_back({ b, (V.row(static_cast<Eigen::Index>(a)) - V.row(b)).norm() });
    return g;
}

// Dijkstra from `from` to `to`; the vertex path including both ends.
std::vector<int> shortestPath(const Graph& g, int from, int to)
{
    std::vector<double> dist(g.size(), std::numeric_limits<double>::infinity());
    std::vector<int> prev(g.size(), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist[static_cast<size_t>(from)] = 0;
    queue.push({ 0.0, from });
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (v == to)
            break;
        if (d > dist[static_cast<size_t>(v)])
            continue;
        for (const auto& [w, length] : g[static_cast<size_t>(v)])
            if (d + length < dist[static_cast<size_t>(w)]) {
                dist[static_cast<size_t>(w)] = d + length;
                prev[static_cast<size_t>(w)] = v;
                queue.push({ d + length, w });
            }
    }
    if (from != to && prev[static_cast<size_t>(to)] < 0)
        fail("import ict-facekit: no skin path from vertex ", from, " to ", to, " (region too small?)");
    std::vector<int> path { to };
    while (path.back() != from)
        path.push_back(prev[static_cast<size_t>(path.back())]);
    std::reverse(path.begin(), path.end());
    return path;
}

// Shortest path through `anchors` in order; `closed` also returns to the first (not repeated).
std::vector<int> pathThrough(const Graph& g, const std::vector<int>& anchors, bool closed = false)
{
    std::vector<int> out { anchors.front() };
    std::vector<int> stops(anchors.begin() + 1, anchors.end());
    if (closed)
        stops.push_back(anchors.front());
    for (int to : stops) {
        const std::vector<int> leg = shortestPath(g, out.back(), to);
        out.insert(out.end(), leg.begin() + 1, leg.end());
    }
    if (closed)
        out.pop_back();
    // A leg that starts by walking back along the previous one (a, b, a) leaves a spike; cut it
    // so that no vertex repeats.
    for (size_t i = 1; i + 1 < out.size();)
        if (out[i - 1] == out[i + 1]) {
            out.erase(out.begin() + static_cast<std::ptrdiff_t>(i), out.begin() + static_cast<std::ptrdiff_t>(i + 2));
            i = std::max<size_t>(1, i - 1);
        } else {
            ++i;
        }
    return out;
}

// Area-weighted unit vertex normals from the triangles whose three vertices lie in [begin, end);
// #V by 3, zero rows elsewhere. Outward for counter-clockwise triangles.
Vertices normalsWithin(const Vertices& V, const Triangles& F, int begin, int end)
{
    Vertices N = Vertices::Zero(V.rows(), 3);
    auto within = [&](int v) { return v >= begin && v < end; };
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        if (within(F(f, 0)) && within(F(f, 1)) && within(F(f, 2))) {
            const Eigen::RowVector3d n = (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0)));
            for (int k = 0; k < 3; ++k)
                N.row(F(f, k)) += n;
        }
    for (Eigen::Index v = 0; v < N.rows(); ++v)
        if (N.row(v).squaredNorm() > 0)
            N.row(v).normalize();
    return N;
}

// nostril_l (side +1) or nostril_r (side -1), the rule of import_ict.h: the boundary of the
// nostril's cavity, grown from its deepest vertex, as a closed loop starting nearest sbal.
// The cavity's vertices inside the rim are appended to `hidden`: seen only from below the nose,
// they are no contour candidates (thesis 4.3.3).
std::vector<int> nostrilRing(const Vertices& V, const Triangles& F, const Graph& g, const Vertices& normals, const std::vector<int>& pie,
    int side, std::vector<int>& hidden)
{
    const int skinEnd = static_cast<int>(g.size());
    const char* name = side > 0 ? "nostril_l" : "nostril_r";
    const int sbal = pie[side > 0 ? 35 : 31], sn = pie[33];
    // The nose base plane through both sbal and Multi-PIE 30; `out` leaves the nose through it
    // (down and forward), `depth` is the height above it into the nose.
    const Eigen::RowVector3d right = V.row(pie[31]);
    const Eigen::RowVector3d out = (V.row(pie[35]) - right).cross(V.row(pie[30]) - right).normalized();
    auto depth = [&](int v) { return (right - V.row(v)).dot(out); };
    int apex = -1;
    for (int v = 0; v < skinEnd; ++v)
        if (side * V(v, 0) > 0 && side * V(v, 0) < side * V(sbal, 0) && (V.row(v) - V.row(sn)).norm() < 20
            && (apex < 0 || depth(v) > depth(apex)))
            apex = v;
    if (apex < 0)
        fail("import ict-facekit: ", name, ": no skin vertex between sn and sbal (region too small?)");

    std::vector<char> inside(static_cast<size_t>(skinEnd), 0);
    std::vector<int> stack { apex };
    inside[static_cast<size_t>(apex)] = 1;
    auto grow = [&](const std::function<bool(int)>& keep) {
        while (!stack.empty()) {
            const int v = stack.back();
            stack.pop_back();
            for (const auto& [w, length] : g[static_cast<size_t>(v)])
                if (!inside[static_cast<size_t>(w)] && keep(w)) {
                    inside[static_cast<size_t>(w)] = 1;
                    stack.push_back(w);
                }
        }
    };
    // The deep vestibule, then its walls out to where the skin turns to face out of the nose base.
    grow([&](int w) { return depth(w) > 4; });
    for (int v = 0; v < skinEnd; ++v)
        if (inside[static_cast<size_t>(v)])
            stack.push_back(v);
    grow([&](int w) { return normals.row(w).dot(out) < 0.3; });

    // The boundary of the triangles inside: directed edges without their reverse.
    std::set<std::pair<int, int>> edges;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        bool all = true;
        for (int k = 0; k < 3; ++k)
            all = all && F(f, k) < skinEnd && inside[static_cast<size_t>(F(f, k))];
        if (all)
            for (int k = 0; k < 3; ++k)
                edges.insert({ F(f, k), F(f, (k + 1) % 3) });
    }
    std::map<int, int> next;
    for (const auto& [a, b] : edges)
        if (!edges.count({ b, a }) && !next.emplace(a, b).second)
            fail("import ict-facekit: ", name, ": the nostril's rim passes vertex ", a, " twice");
    if (next.empty())
        fail("import ict-facekit: ", name, ": no nostril cavity found at vertex ", apex);
    std::vector<int> ring { next.begin()->first };
    while (ring.size() <= next.size()) {
        const auto it = next.find(ring.back());
        if (it == next.end() || it->second == ring.front())
            break;
        ring.push_back(it->second);
    }
    if (ring.size() != next.size())
        fail("import ict-facekit: ", name, ": the nostril's rim is not one closed loop (", ring.size(), " of ", next.size(), " edges)");
    auto fromSbal = [&](int v) { return (V.row(v) - V.row(sbal)).norm(); };
    for (int v : ring)
        if (fromSbal(v) > 25)
            fail("import ict-facekit: ", name, ": rim vertex ", v, " is ", fromSbal(v), " mm from sbal (cavity leaked)");
    std::rotate(
        ring.begin(), std::min_element(ring.begin(), ring.end(), [&](int a, int b) { return fromSbal(a) < fromSbal(b); }), ring.end());
    const std::set<int> rim(ring.begin(), ring.end());
    for (int v = 0; v < skinEnd; ++v)
        if (inside[static_cast<size_t>(v)] && !rim.count(v))
            hidden.push_back(v);
    return ring;
}

// The geometric labelling rules of import_ict.h, on the region's neutral in mm.
void labelSkin(Manifest& m, const Vertices& V, const std::vector<int>& pie, int skinEnd, int prn)
{
    auto y = [&](int v) { return V(v, 1); };
    auto z = [&](int v) { return V(v, 2); };
    const Graph g = skinGraph(V, m.topology, skinEnd);
    auto best = [&](const std::function<bool(int)>& keep, const std::function<double(int)>& score, const char* what) {
        int out = -1;
        for (int v = 0; v < skinEnd; ++v)
            if (keep(v) && (out < 0 || score(v) > score(out)))
                out = v;
        if (out < 0)
            fail("import ict-facekit: no skin vertex for ", what, " (region too small?)");
        return out;
    };
    const double eyeZ = 0.5 * (z(pie[36]) + z(pie[45]));
    auto midline = [&](int v, double lo, double hi) {
        return std::abs(V(v, 0)) < 0.05 && y(v) >= std::min(lo, hi) && y(v) <= std::max(lo, hi) && z(v) > eyeZ - 20;
    };

    auto& L = m.landmarks;
    L["ex_r"] = pie[36];
    L["en_r"] = pie[39];
    L["en_l"] = pie[42];
    L["ex_l"] = pie[45];
    L["ch_r"] = pie[48];
    L["ch_l"] = pie[54];
    L["ls"] = pie[51];
    L["li"] = pie[57];
    L["sto"] = pie[62];
    L["sn"] = pie[33];
    L["sbal_r"] = pie[31];
    L["sbal_l"] = pie[35];
    L["cph_r"] = pie[50];
    L["cph_l"] = pie[52];
    L["n"] = pie[27];
    L["cs1"] = pie[29];
    L["gn"] = pie[8];
    L["obs_r"] = pie[0];
    L["obs_l"] = pie[16];
    L["prn"] = prn;
    const double browY = 0.5 * (y(pie[21]) + y(pie[22]));
    L["g"] = best([&](int v) { return midline(v, y(pie[27]), browY + 10); }, z, "g");
    L["s"] = best([&](int v) { return midline(v, y(pie[29]), y(L["g"])); }, [&](int v) { return -z(v); }, "s");
    L["pg"] = best([&](int v) { return midline(v, y(pie[8]), y(pie[57]) - 5); }, z, "pg");
    L["sl"] = best([&](int v) { return midline(v, y(L["pg"]), y(pie[57])); }, [&](int v) { return -z(v); }, "sl");
    for (int side : { 1, -1 }) {
        const std::string sfx = side > 0 ? "_l" : "_r";
        const int sbal = L["sbal" + sfx];
        L["al" + sfx] = best(
            [&](int v) {
                return side * V(v, 0) > 0 && side * V(v, 0) < 2.5 * std::abs(V(sbal, 0)) && y(v) >= y(sbal) - 2 && y(v) <= y(L["prn"])
                    && z(v) >= z(sbal) - 2;
            },
            [&](int v) { return side * V(v, 0); }, "al");
    }

    auto& C = m.contours;
    C["eyebrow_r"] = pathThrough(g, { pie[21], pie[20], pie[19], pie[18], pie[17] });
    C["eyebrow_l"] = pathThrough(g, { pie[22], pie[23], pie[24], pie[25], pie[26] });
    const std::vector<int> upperR = pathThrough(g, { pie[39], pie[38], pie[37], pie[36] });
    const std::vector<int> lowerR = pathThrough(g, { pie[36], pie[41], pie[40], pie[39] });
    const std::vector<int> upperL = pathThrough(g, { pie[42], pie[43], pie[44], pie[45] });
    const std::vector<int> lowerL = pathThrough(g, { pie[45], pie[46], pie[47], pie[42] });
    C["eye_socket_r"] = pathThrough(g, { pie[39], pie[38], pie[37], pie[36], pie[41], pie[40] }, true);
    C["eye_socket_l"] = pathThrough(g, { pie[42], pie[43], pie[44], pie[45], pie[46], pie[47] }, true);
    auto highest = [&](const std::vector<int>& path, int sign) {
        return *std::max_element(path.begin(), path.end(), [&](int a, int b) { return sign * y(a) < sign * y(b); });
    };
    L["ps_r"] = highest(upperR, 1);
    L["pi_r"] = highest(lowerR, -1);
    L["ps_l"] = highest(upperL, 1);
    L["pi_l"] = highest(lowerL, -1);
    for (const std::string sfx : { "_l", "_r" }) {
        const std::vector<int>& brow = C["eyebrow" + sfx];
        const double px = V(L["ps" + sfx], 0);
        L["os" + sfx]
            = *std::min_element(brow.begin(), brow.end(), [&](int a, int b) { return std::abs(V(a, 0) - px) < std::abs(V(b, 0) - px); });
        const std::vector<int> up = shortestPath(g, L["en" + sfx], brow.front());
        L["mf" + sfx] = up[up.size() / 3];
    }
    C["lip_upper_outer"] = pathThrough(g, { pie[48], pie[49], pie[50], pie[51], pie[52], pie[53], pie[54] });
    C["lip_lower_outer"] = pathThrough(g, { pie[48], pie[59], pie[58], pie[57], pie[56], pie[55], pie[54] });
    C["lip_upper_inner"] = pathThrough(g, { pie[48], pie[60], pie[61], pie[62], pie[63], pie[64], pie[54] });
    C["lip_lower_inner"] = pathThrough(g, { pie[48], pie[60], pie[67], pie[66], pie[65], pie[64], pie[54] });
    const Vertices normals = normalsWithin(V, m.topology, 0, skinEnd);
    C["nostril_l"] = nostrilRing(V, m.topology, g, normals, pie, 1, m.excluded);
    C["nostril_r"] = nostrilRing(V, m.topology, g, normals, pie, -1, m.excluded);
    auto& M = m.mpeg4;
    M["2.1"] = L["gn"];
    M["2.2"] = pie[62];
    M["2.3"] = pie[66];
    M["2.4"] = pie[64];
    M["2.5"] = pie[60];
    M["2.6"] = pie[63];
    M["2.7"] = pie[61];
    M["2.8"] = pie[65];
    M["2.9"] = pie[67];
    M["2.10"] = L["pg"];
    M["3.1"] = L["ps_l"];
    M["3.2"] = L["ps_r"];
    M["3.3"] = L["pi_l"];
    M["3.4"] = L["pi_r"];
    M["3.7"] = L["ex_l"];
    M["3.12"] = L["ex_r"];
    M["3.11"] = L["en_l"];
    M["3.8"] = L["en_r"];
    M["4.1"] = pie[22];
    M["4.2"] = pie[21];
    M["4.3"] = pie[24];
    M["4.4"] = pie[19];
    M["4.5"] = pie[26];
    M["4.6"] = pie[17];
    for (int side : { 1, -1 }) {
        const int ex = side > 0 ? L["ex_l"] : L["ex_r"];
        const double ty = 0.5 * (y(ex) + y(L["prn"]));
        M[side > 0 ? "5.3" : "5.4"]
            = best([&](int v) { return std::abs(V(v, 0) - V(ex, 0)) < 3 && std::abs(y(v) - ty) < 3; }, z, "cheekbone");
    }
    M["8.1"] = L["ls"];
    M["8.2"] = L["li"];
    M["8.3"] = L["ch_l"];
    M["8.4"] = L["ch_r"];
    M["8.5"] = pie[53];
    M["8.6"] = pie[49];
    M["8.7"] = pie[55];
    M["8.8"] = pie[59];
    M["8.9"] = L["cph_r"];
    M["8.10"] = L["cph_l"];
    M["9.1"] = L["al_l"];
    M["9.2"] = L["al_r"];
    M["9.3"] = L["prn"];
    M["9.15"] = L["sn"];
}

// prn: the most forward skin vertex moves a little from identity to identity, so take the
// vertex near Multi-PIE point 30 that lies within 3 mm of each identity's most forward skin
// vertex for the most of 64 identities drawn with seed 0 (ties: the smaller mean distance).
// A minimax choice is worse: it serves the extreme identities at the cost of typical ones.
// "Forward" is the face's own, (ex_l - ex_r) x (n - gn), since real heads are pitched differently.
int robustTip(const Vertices& neutral, const Eigen::MatrixXd& modes, const std::vector<int>& pie, int skinEnd)
{
    std::vector<int> candidates;
    for (int v = 0; v < skinEnd; ++v)
        if ((neutral.row(v) - neutral.row(pie[30])).norm() < 10)
            candidates.push_back(v);
    std::vector<int> within(candidates.size(), 0);
    std::vector<double> total(candidates.size(), 0);
    for (int j = 0; j < 64; ++j) {
        const Eigen::VectorXd c = ictCoefficients(0, j, static_cast<int>(modes.cols()));
        auto position = [&](int v) {
            Eigen::RowVector3d p = neutral.row(v);
            for (int k = 0; k < 3; ++k)
                p(k) += modes.row(3 * v + k).dot(c);
            return p;
        };
        const Eigen::RowVector3d forward = (position(pie[45]) - position(pie[36])).cross(position(pie[27]) - position(pie[8])).normalized();
        int front = 0;
        double frontZ = -std::numeric_limits<double>::infinity();
        for (int v = 0; v < skinEnd; ++v) {
            const double zv = position(v).dot(forward);
            if (zv > frontZ) {
                frontZ = zv;
                front = v;
            }
        }
        const Eigen::RowVector3d tip = position(front);
        for (size_t i = 0; i < candidates.size(); ++i) {
            const double distance = (position(candidates[i]) - tip).norm();
            within[i] += distance < 3.0;
            total[i] += distance;
        }
    }
    size_t best = 0;
    for (size_t i = 1; i < candidates.size(); ++i)
        if (within[i] > within[best] || (within[i] == within[best] && total[i] < total[best]))
            best = i;
    return candidates[best];
}

// 9.10 and 9.11 on the lower teeth: teeth are connected components of the component.
void labelLowerTeeth(Manifest& m, const Vertices& V, const Component& teeth)
{
    std::vector<int> parent(static_cast<size_t>(teeth.size()));
    for (size_t i = 0; i < parent.size(); ++i)
        parent[i] = static_cast<int>(i);
    std::function<int(int)> find = [&](int x) {
        while (parent[static_cast<size_t>(x)] != x)
            x = parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
        return x;
    };
    for (Eigen::Index f = 0; f < m.topology.rows(); ++f)
        if (teeth.contains(m.topology(f, 0)))
            for (int k = 1; k < 3; ++k)
                parent[static_cast<size_t>(find(m.topology(f, k) - teeth.begin))] = find(m.topology(f, 0) - teeth.begin);
    std::map<int, std::vector<int>> tooth;
    for (int v = teeth.begin; v < teeth.end; ++v)
        tooth[find(v - teeth.begin)].push_back(v);
    std::vector<std::pair<double, int>> left; // (mean x, top vertex) of teeth on the +x side
    int centre = -1;
    for (const auto& [root, vs] : tooth) {
        double mx = 0;
        int top = vs.front();
        for (int v : vs) {
            mx += V(v, 0);
            if (V(v, 1) > V(top, 1))
                top = v;
        }
        mx /= static_cast<double>(vs.size());
        if (mx > 0)
            left.push_back({ mx, top });
    }
    std::sort(left.begin(), left.end());
    if (left.size() < 3)
        fail("import ict-facekit: the lower teeth have ", left.size(), " teeth on the left, expected at least 3");
    for (int v = teeth.begin; v < teeth.end; ++v)
        if (std::abs(V(v, 0)) < 3 && (centre < 0 || V(v, 1) > V(centre, 1)))
            centre = v;
    m.mpeg4["9.10"] = centre;
    m.mpeg4["9.11"] = left[2].second;
}

// Group 6 on the tongue (import_ict.h): tip, dorsum centre and the two borders at mid depth.
void labelTongue(Manifest& m, const Vertices& V, const Component& tongue)
{
    const Vertices N = normalsWithin(V, m.topology, tongue.begin, tongue.end);
    int tip = -1;
    double back = std::numeric_limits<double>::infinity();
    for (int v = tongue.begin; v < tongue.end; ++v) {
        back = std::min(back, V(v, 2));
        if (std::abs(V(v, 0)) < 2 && (tip < 0 || V(v, 2) > V(tip, 2)))
            tip = v;
    }
    if (tip < 0)
        fail("import ict-facekit: the tongue [", tongue.begin, ", ", tongue.end, ") has no vertex near the midline");
    const double mid = 0.5 * (V(tip, 2) + back);
    int centre = -1, left = -1, right = -1;
    for (int v = tongue.begin; v < tongue.end; ++v) {
        if (std::abs(V(v, 2) - mid) >= 3)
            continue;
        if (std::abs(V(v, 0)) < 1 && (centre < 0 || V(v, 1) > V(centre, 1)))
            centre = v;
        if (N(v, 1) > 0 && (left < 0 || V(v, 0) > V(left, 0)))
            left = v;
        if (N(v, 1) > 0 && (right < 0 || V(v, 0) < V(right, 0)))
            right = v;
    }
    if (centre < 0 || left < 0 || right < 0)
        fail("import ict-facekit: the tongue [", tongue.begin, ", ", tongue.end, ") has no midline or upper surface vertex at mid depth");
    m.mpeg4["6.1"] = tip;
    m.mpeg4["6.2"] = centre;
    m.mpeg4["6.3"] = left;
    m.mpeg4["6.4"] = right;
}

} // namespace

const char* ictRegionName(IctRegion region)
{
    switch (region) {
    case IctRegion::NarrowFace:
        return "narrow";
    case IctRegion::Face:
        return "face";
    case IctRegion::HeadNeck:
        return "head";
    }
    return "?";
}

IctRegion parseIctRegion(const std::string& text)
{
    return parseName(text, std::array { IctRegion::NarrowFace, IctRegion::Face, IctRegion::HeadNeck }, ictRegionName, "region");
}

IctPoseRecipes readIctPoseRecipes(const fs::path& path)
{
    std::ifstream in(path);
    if (!in)
        fail(path.string(), ": cannot open the pose recipe file");
    nlohmann::ordered_json doc;
    try {
        doc = nlohmann::ordered_json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        fail(path.string(), ": not valid JSON: ", e.what());
    }
    if (!doc.is_object() || doc.empty())
        fail(path.string(), ": expected an object {\"pose\": {\"blendshape\": weight}}");
    IctPoseRecipes out;
    std::set<std::string> names;
    for (const auto& [name, shapes] : doc.items()) {
        if (name.empty() || name.find_first_of("/\\") != std::string::npos || name[0] == '.')
            fail(path.string(), ": pose name '", name, "' is empty or not file-name safe");
        if (!names.insert(name).second)
            fail(path.string(), ": ", name, ": duplicate pose");
        if (!shapes.is_object())
            fail(path.string(), ": ", name, ": expected an object {\"blendshape\": weight}");
        std::map<std::string, double> recipe;
        for (const auto& [shape, weight] : shapes.items()) {
            if (!weight.is_number() || !std::isfinite(weight.get<double>()))
                fail(path.string(), ": ", name, ".", shape, ": weight '", weight.dump(), "' is not a finite number");
            recipe[shape] = weight.get<double>();
        }
        out.push_back({ name, recipe });
    }
    return out;
}

IctModel loadIctModel(const fs::path& path, const IctOptions& options, const std::vector<std::string>& expressions)
{
    const fs::path folder = modelFolder(path);
    const fs::path neutralFile = folder / "generic_neutral_mesh.obj";
    const Mesh full = readObj(neutralFile);
    if (full.vertexCount() != kIctVertexCount)
        fail(neutralFile.string(), ": has ", full.vertexCount(), " vertices, the ICT Face Model has ", kIctVertexCount);
    const std::vector<int> pie = readLandmarkIndices(folder);

    // Kept vertex ranges, in output order; skin first.
    const int skinEnd = options.region == IctRegion::NarrowFace ? 6706 : options.region == IctRegion::Face ? 9409 : 11248;
    std::vector<Range> ranges { { "skin", 0, skinEnd } };
    if (options.eyes)
        for (const Range& r : { kEyeSocketLeft, kEyeSocketRight, kEyeLeft, kEyeRight })
            ranges.push_back(r);
    if (options.mouth)
        for (const Range& r : { kMouthSocket, kGums, kTongue, kTeethUpper, kTeethLower })
            ranges.push_back(r);
    std::vector<int> newIndex(kIctVertexCount, -1), kept;
    IctModel model;
    Manifest& m = model.labels;
    for (const Range& r : ranges) {
        m.components.push_back({ r.name, static_cast<int>(kept.size()), static_cast<int>(kept.size()) + r.end - r.begin });
        for (int v = r.begin; v < r.end; ++v) {
            newIndex[static_cast<size_t>(v)] = static_cast<int>(kept.size());
            kept.push_back(v);
        }
        if (std::string(r.name).find("socket") != std::string::npos)
            for (int v = m.components.back().begin; v < m.components.back().end; ++v)
                m.excluded.push_back(v);
    }
    m.vertexCount = static_cast<int>(kept.size());
    std::vector<Eigen::Index> faces;
    for (Eigen::Index f = 0; f < full.triangleCount(); ++f)
        if (newIndex[full.F(f, 0)] >= 0 && newIndex[full.F(f, 1)] >= 0 && newIndex[full.F(f, 2)] >= 0)
            faces.push_back(f);
    m.topology.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (size_t i = 0; i < faces.size(); ++i)
        for (int k = 0; k < 3; ++k)
            m.topology(static_cast<Eigen::Index>(i), k) = newIndex[full.F(faces[i], k)];

    auto restrict = [&](const Vertices& V) {
        Vertices out(static_cast<Eigen::Index>(kept.size()), 3);
        for (size_t i = 0; i < kept.size(); ++i)
            out.row(static_cast<Eigen::Index>(i)) = kCmToMm * V.row(kept[i]);
        return out;
    };
    model.neutral = restrict(full.V);
    const Eigen::RowVectorXd neutralRow = flatten(model.neutral);
    auto delta = [&](const fs::path& file) -> Eigen::RowVectorXd {
        const Vertices V = readObjPositions(file);
        if (V.rows() != kIctVertexCount)
            fail(file.string(), ": has ", V.rows(), " vertices, ", neutralFile.filename().string(), " has ", kIctVertexCount);
        return flatten(restrict(V)) - neutralRow;
    };

    std::vector<fs::path> identityFiles;
    for (int i = 0;; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "identity%03d.obj", i);
        if (!fs::is_regular_file(folder / name))
            break;
        identityFiles.push_back(folder / name);
    }
    if (identityFiles.empty())
        fail(folder.string(), ": no identity000.obj (the identity modes)");
    model.identityModes.resize(3 * m.vertexCount, static_cast<Eigen::Index>(identityFiles.size()));
    for (size_t i = 0; i < identityFiles.size(); ++i)
        model.identityModes.col(static_cast<Eigen::Index>(i)) = delta(identityFiles[i]).transpose();
    for (const std::string& name : expressions) {
        const fs::path file = folder / (name + ".obj");
        if (!fs::is_regular_file(file))
            fail(file.string(), ": missing (expression '", name, "' used by a pose recipe)");
        model.expressions[name] = delta(file);
    }

    std::vector<int> landmarks;
    for (int v : pie) {
        if (newIndex[static_cast<size_t>(v)] < 0 || newIndex[static_cast<size_t>(v)] >= skinEnd)
            fail(folder.string(), ": landmark vertex ", v, " is outside the ", ictRegionName(options.region), " region");
        landmarks.push_back(newIndex[static_cast<size_t>(v)]);
    }
    labelSkin(m, model.neutral, landmarks, skinEnd, robustTip(model.neutral, model.identityModes, landmarks, skinEnd));
    if (options.mouth) {
        labelTongue(m, model.neutral, *m.component("tongue"));
        labelLowerTeeth(m, model.neutral, *m.component("teeth_lower"));
    }
    validateManifest(m, "import ict-facekit");
    return model;
}

Eigen::VectorXd ictCoefficients(std::uint64_t seed, int index, int modes)
{
    Random rng(splitMix64(splitMix64(seed) ^ static_cast<std::uint64_t>(index)), BoxMuller::PlusOne);
    Eigen::VectorXd c(modes);
    for (int i = 0; i < modes; ++i)
        c(i) = rng.normal();
    return c;
}

Vertices ictIdentity(const IctModel& model, const Eigen::VectorXd& coefficients)
{
    if (coefficients.size() != model.identityModes.cols())
        fail("ictIdentity: ", coefficients.size(), " coefficients for ", model.identityModes.cols(), " modes");
    const Eigen::RowVectorXd row = flatten(model.neutral) + (model.identityModes * coefficients).transpose();
    return unflatten(row);
}

Vertices ictPose(const IctModel& model, const Vertices& identity, const std::map<std::string, double>& recipe)
{
    Eigen::RowVectorXd row = flatten(identity);
    for (const auto& [name, weight] : recipe) {
        const auto it = model.expressions.find(name);
        if (it == model.expressions.end())
            fail("ictPose: expression '", name, "' was not loaded");
        row += weight * it->second;
    }
    return unflatten(row);
}

Manifest writeIctDataset(const fs::path& path, const fs::path& output, const IctOptions& options)
{
    if (options.identities < 1)
        fail("import ict-facekit: --identities ", options.identities, ": need at least 1");
    IctPoseRecipes recipes;
    std::vector<std::string> expressions;
    if (options.poses) {
        recipes = readIctPoseRecipes(options.recipes);
        std::set<std::string> names;
        for (const auto& [pose, recipe] : recipes)
            for (const auto& [shape, weight] : recipe)
                names.insert(shape);
        expressions.assign(names.begin(), names.end());
    }
    const IctModel model = loadIctModel(path, options, expressions);

    Manifest m = model.labels;
    Simplification simplification;
    const bool simplify = options.vertices > 0;
    if (simplify) {
        simplification = simplifyTopology(model.neutral, m, options.vertices);
        m = simplifyManifest(m, simplification);
    }
    const std::vector<Role> roles = synthRoles(options.identities);
    const int posed = !options.poses ? 0
        : options.poseIdentities < 0 ? options.identities
                                     : std::min(options.poseIdentities, options.identities);
    for (int i = 0; i < options.identities; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "face_%04d", i);
        m.samples.push_back({ name, fs::path("faces") / (std::string(name) + ".ply"), roles[static_cast<size_t>(i)] });
        if (i < posed)
            for (const auto& [pose, recipe] : recipes)
                m.poses.push_back({ name, pose, fs::path("poses") / name / (pose + ".ply") });
    }

    const int modes = static_cast<int>(model.identityModes.cols());
    writeDataset(output, m, [&](const fs::path& tmp) {
        fs::create_directories(tmp / "faces");
        auto write = [&](const fs::path& file, const Vertices& V) {
            writePly(tmp / file, Mesh { simplify ? keepVertices(V, simplification) : V, m.topology });
        };
        size_t pose = 0;
        for (int i = 0; i < options.identities; ++i) {
            const Vertices identity = ictIdentity(model, ictCoefficients(options.seed, i, modes));
            write(m.samples[static_cast<size_t>(i)].file, identity);
            if (i < posed) {
                fs::create_directories(tmp / "poses" / m.samples[static_cast<size_t>(i)].name);
                for (const auto& [poseName, recipe] : recipes)
                    write(m.poses[pose++].file, ictPose(model, identity, recipe));
            }
        }
    });
    return m;
}

} // namespace facesketch::dataset

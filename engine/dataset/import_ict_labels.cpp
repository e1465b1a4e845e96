// The labelling rules of the ICT import (import_ict_labels.h, import_ict.h).
//
// Sources: the 68-point Multi-PIE / iBUG 300-W landmark scheme (Sagonas et al., 300 Faces
// in-the-Wild Challenge, 2013); landmark definitions of thesis Table 3.1 (Farkas, Anthropometry
// of the Head and Face, 1994); MPEG-4 feature points (ISO/IEC 14496-2 Annex C); Dijkstra's
// shortest paths (Dijkstra, 1959).
#include "dataset/import_ict_labels.h"

#include "core/error.h"
#include "dataset/import_ict.h"
#include "geometry/graph.h"
#include "geometry/normals.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>

namespace facesketch::dataset::ict {

namespace {

using Graph = EdgeGraph;

// Shortest path through `anchors` in order; `closed` also returns to the first (not repeated).
std::vector<int> pathThrough(const Graph& g, const std::vector<int>& anchors, bool closed = false)
{
    std::vector<int> out { anchors.front() };
    std::vector<int> stops(anchors.begin() + 1, anchors.end());
    if (closed)
        stops.push_back(anchors.front());
    for (int to : stops) {
        const std::vector<int> leg = shortestPath(g, out.back(), to);
        if (leg.empty())
            fail("import ict-facekit: no skin path from vertex ", out.back(), " to ", to, " (region too small?)");
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

// Area-weighted unit vertex normals (geometry/normals.h) from the triangles whose three
// vertices lie in [begin, end); #V by 3, zero rows elsewhere. Outward for counter-clockwise
// triangles.
Vertices normalsWithin(const Vertices& V, const Triangles& F, int begin, int end)
{
    auto within = [&](int v) { return v >= begin && v < end; };
    std::vector<Eigen::Index> keep;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
        if (within(F(f, 0)) && within(F(f, 1)) && within(F(f, 2)))
            keep.push_back(f);
    return vertexNormals(Mesh { V, F(keep, Eigen::all) });
}

// nostril_l (side +1) or nostril_r (side -1), the rule of import_ict.h: the boundary of the
// nostril's cavity, grown from its deepest vertex, as a closed loop starting nearest sbal.
// The cavity's vertices inside the rim are appended to `hidden`: seen only from below the nose,
// they are no contour candidates (thesis 4.3.3).
std::vector<int> nostrilRing(const Vertices& V, const Triangles& F, const Graph& g, const Vertices& normals, const std::vector<int>& pie,
    int side, std::vector<int>& hidden)
{
    const int skinEnd = static_cast<int>(g.adjacency.size());
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
            for (const auto& [w, length] : g.adjacency[static_cast<size_t>(v)])
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

// The skin vertex in [0, skinEnd) of greatest `score` among those `keep` accepts (the first on
// ties); throws Error naming `what` if there is none.
int bestSkinVertex(int skinEnd, const std::function<bool(int)>& keep, const std::function<double(int)>& score, const char* what)
{
    int out = -1;
    for (int v = 0; v < skinEnd; ++v)
        if (keep(v) && (out < 0 || score(v) > score(out)))
            out = v;
    if (out < 0)
        fail("import ict-facekit: no skin vertex for ", what, " (region too small?)");
    return out;
}

// The craniofacial landmarks of the skin (import_ict.h "Landmarks"): Multi-PIE points where they
// coincide, geometric rules on the midline and the alae otherwise; prn is given (ictRobustTip).
void labelSkinLandmarks(Manifest& m, const Vertices& V, const std::vector<int>& pie, int skinEnd, int prn)
{
    auto y = [&](int v) { return V(v, 1); };
    auto z = [&](int v) { return V(v, 2); };
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
    L["g"] = bestSkinVertex(
        skinEnd, [&](int v) { return midline(v, y(pie[27]), browY + 10); }, z, "g");
    L["s"] = bestSkinVertex(
        skinEnd, [&](int v) { return midline(v, y(pie[29]), y(L["g"])); }, [&](int v) { return -z(v); }, "s");
    L["pg"] = bestSkinVertex(
        skinEnd, [&](int v) { return midline(v, y(pie[8]), y(pie[57]) - 5); }, z, "pg");
    L["sl"] = bestSkinVertex(
        skinEnd, [&](int v) { return midline(v, y(L["pg"]), y(pie[57])); }, [&](int v) { return -z(v); }, "sl");
    for (int side : { 1, -1 }) {
        const std::string sfx = side > 0 ? "_l" : "_r";
        const int sbal = L["sbal" + sfx];
        L["al" + sfx] = bestSkinVertex(
            skinEnd,
            [&](int v) {
                return side * V(v, 0) > 0 && side * V(v, 0) < 2.5 * std::abs(V(sbal, 0)) && y(v) >= y(sbal) - 2 && y(v) <= y(L["prn"])
                    && z(v) >= z(sbal) - 2;
            },
            [&](int v) { return side * V(v, 0); }, "al");
    }
}

// The labelled contours (thesis 4.3.3) as shortest skin-edge paths through Multi-PIE points,
// the eye and brow landmarks read off them, and the nostril rims (whose insides join
// m.excluded).
void labelSkinContours(Manifest& m, const Vertices& V, const std::vector<int>& pie, int skinEnd)
{
    auto y = [&](int v) { return V(v, 1); };
    auto& L = m.landmarks;
    const Graph g = buildEdgeGraph(V, m.topology, skinEnd);
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
}

// The 40 skin MPEG-4 feature points (thesis 5.2), from the landmarks and Multi-PIE points.
void labelSkinMpeg4(Manifest& m, const Vertices& V, const std::vector<int>& pie, int skinEnd)
{
    auto y = [&](int v) { return V(v, 1); };
    auto z = [&](int v) { return V(v, 2); };
    auto& L = m.landmarks;
    auto& M = m.mpeg4;
    labelMpeg4FromLandmarks(m);
    M["2.2"] = pie[62];
    M["2.3"] = pie[66];
    M["2.4"] = pie[64];
    M["2.5"] = pie[60];
    M["2.6"] = pie[63];
    M["2.7"] = pie[61];
    M["2.8"] = pie[65];
    M["2.9"] = pie[67];
    M["4.1"] = pie[22];
    M["4.2"] = pie[21];
    M["4.3"] = pie[24];
    M["4.4"] = pie[19];
    M["4.5"] = pie[26];
    M["4.6"] = pie[17];
    for (int side : { 1, -1 }) {
        const int ex = side > 0 ? L["ex_l"] : L["ex_r"];
        const double ty = 0.5 * (y(ex) + y(L["prn"]));
        M[side > 0 ? "5.3" : "5.4"] = bestSkinVertex(
            skinEnd, [&](int v) { return std::abs(V(v, 0) - V(ex, 0)) < 3 && std::abs(y(v) - ty) < 3; }, z, "cheekbone");
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

} // namespace

void labelSkin(Manifest& m, const Vertices& V, const std::vector<int>& pie, int skinEnd, int prn)
{
    labelSkinLandmarks(m, V, pie, skinEnd, prn);
    labelSkinContours(m, V, pie, skinEnd);
    labelSkinMpeg4(m, V, pie, skinEnd);
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
    // Every draw's offsets in one product: a row of the column-major modes lies a column's
    // height apart in memory (640 KB at full resolution), so one dot product per coordinate
    // missed the cache on every coefficient; two imports side by side took 20 times as long.
    constexpr int kDraws = 64;
    Eigen::MatrixXd coefficients(modes.cols(), kDraws);
    for (int j = 0; j < kDraws; ++j)
        coefficients.col(j) = ictCoefficients(0, j, static_cast<int>(modes.cols()));
    const Eigen::MatrixXd offsets = modes * coefficients;
    for (int j = 0; j < kDraws; ++j) {
        auto position = [&](int v) { return Eigen::RowVector3d(neutral.row(v) + offsets.block<3, 1>(3 * v, j).transpose()); };
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

} // namespace facesketch::dataset::ict

// Topology of the synthetic face (face_generator.h): the skin grid with its eye and mouth slits,
// eyeballs, dental arches and tongue, and the labels every face of a resolution shares:
// craniofacial landmarks (thesis Table 3.1), the 46 MPEG-4 feature points used for posing
// (thesis 5.2: 40 skin, 4 tongue, 2 lower teeth) and the labelled contours (thesis 4.3.3).
#include "dataset/synth/face_generator.h"

#include "dataset/synth/face_frame.h"

#include "core/error.h"
#include "core/names.h"

#include <algorithm>
#include <cmath>

namespace facesketch::dataset {

const char* resolutionName(Resolution r)
{
    switch (r) {
    case Resolution::Low:
        return "low";
    case Resolution::High:
        return "high";
    case Resolution::Ultra:
        return "ultra";
    }
    return "?";
}

Resolution parseResolution(const std::string& text)
{
    return parseName(text, std::array { Resolution::Low, Resolution::High, Resolution::Ultra }, resolutionName, "resolution");
}

int FaceTopology::lowerCopy(int row, int col) const
{
    // Lower copies follow the grid: left eye, right eye, then mouth, each in column order.
    const int s = col - mid;
    int index = rows * cols;
    const int eyeInterior = sEx - sEn - 1;
    if (row == rowKnot[3]) {
        if (s < 0 && -s > sEn && -s < sEx)
            return index + (sEx + s - 1); // right eye: s = -sEx+1 .. -sEn-1
        index += eyeInterior;
        if (s > 0 && s > sEn && s < sEx)
            return index + (s - sEn - 1);
        return -1;
    }
    if (row == rowKnot[7] && std::abs(s) < sCh)
        return index + 2 * eyeInterior + (s + sCh - 1);
    return -1;
}

namespace {

struct Spec {
    int colSegments[4];  // mid->en, en->ch, ch->ex, ex->side
    int rowSegments[11]; // top, brow, n, eye, prn, sn, ls, sto, li, pg, gn, bottom
    int eyeRings, eyeSegments, archSamples, archSection, tongueRings, tongueSegments;
};

Spec spec(Resolution r)
{
    switch (r) {
    case Resolution::Low:
        return { { 3, 2, 3, 5 }, { 3, 1, 2, 5, 2, 2, 2, 2, 2, 2, 3 }, 6, 7, 7, 4, 4, 6 };
    case Resolution::High:
        // 8 rows from prn to sn and 9 from the eyes to prn (5 and 12 until v8): the nostrils'
        // openings and the columella between them need rows (face_shape.cpp, vestibule()).
        // 5 rows from the brow to n and 6 from the top to the brow (3 and 8 until v12): the
        // brow ridge lies between them, and on rows 7-10 mm apart it was a faceted bar
        // (docs/realism.md, curvature maps); the forehead above it is nearly flat. 6 rows from the
        // brow to n and 5 from n to the eyes since v21 (5 and 6 before): n came 6 mm nearer the
        // eyes (face_frame.cpp), and on six rows 1.7 mm apart the upper lids' triangles turned
        // over in 4 eye poses of 40 faces (v20: 2 poses, now none; docs/realism.md "v21").
        return { { 9, 6, 8, 14 }, { 6, 6, 5, 9, 8, 5, 5, 5, 5, 6, 8 }, 13, 13, 25, 8, 10, 14 };
    case Resolution::Ultra:
        // 12 rows from the brow to n and 7 from n to the eyes since v21 (6 and 13 before): with n
        // 7 mm above the eyes, 13 rows 0.55 mm apart let the upper lids' triangles of a short eye
        // turn over in 8 of its eye and brow poses (seed 11, face 5); on 7 rows 1 mm apart, as
        // v20's were, in 1 (docs/realism.md "v21").
        return { { 19, 13, 17, 30 }, { 17, 12, 7, 25, 10, 11, 10, 10, 11, 12, 17 }, 24, 25, 49, 16, 20, 28 };
    }
    return spec(Resolution::Low);
}

// A closed UV sphere: pole, rings x segments, pole; triangles counter-clockwise from outside
// when the poles are +y (first) and -y (last) and segment angle grows from +z towards +x.
void addSphere(std::vector<Eigen::Vector3i>& tris, int base, int rings, int segments)
{
    const int north = base, south = base + 1 + rings * segments;
    auto ring = [&](int i, int j) { return base + 1 + i * segments + (j % segments); };
    for (int j = 0; j < segments; ++j)
        tris.emplace_back(north, ring(0, j), ring(0, j + 1));
    for (int i = 0; i + 1 < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            tris.emplace_back(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
            tris.emplace_back(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
        }
    for (int j = 0; j < segments; ++j)
        tris.emplace_back(south, ring(rings - 1, j + 1), ring(rings - 1, j));
}

// A capped tube: cap, samples x section rings, cap. Orientation is fixed up by the geometry
// code's convention (section angle grows counter-clockwise seen from the tube's start).
void addTube(std::vector<Eigen::Vector3i>& tris, int base, int samples, int section)
{
    const int start = base, end = base + 1 + samples * section;
    auto ring = [&](int i, int j) { return base + 1 + i * section + (j % section); };
    for (int j = 0; j < section; ++j)
        tris.emplace_back(start, ring(0, j + 1), ring(0, j));
    for (int i = 0; i + 1 < samples; ++i)
        for (int j = 0; j < section; ++j) {
            tris.emplace_back(ring(i, j), ring(i, j + 1), ring(i + 1, j + 1));
            tris.emplace_back(ring(i, j), ring(i + 1, j + 1), ring(i + 1, j));
        }
    for (int j = 0; j < section; ++j)
        tris.emplace_back(end, ring(samples - 1, j), ring(samples - 1, j + 1));
}

// The grid's size, knot rows and columns, and the closed parts' resolutions.
FaceTopology layout(Resolution resolution)
{
    const Spec sp = spec(resolution);
    FaceTopology t;
    t.resolution = resolution;
    t.sEn = sp.colSegments[0];
    t.sCh = t.sEn + sp.colSegments[1];
    t.sEx = t.sCh + sp.colSegments[2];
    t.mid = t.sEx + sp.colSegments[3];
    t.cols = 2 * t.mid + 1;
    t.rowKnot.push_back(0);
    for (int k = 0; k < 11; ++k)
        t.rowKnot.push_back(t.rowKnot.back() + sp.rowSegments[k]);
    t.rows = t.rowKnot.back() + 1;
    t.eyeRings = sp.eyeRings;
    t.eyeSegments = sp.eyeSegments;
    t.archSamples = sp.archSamples;
    t.archSection = sp.archSection;
    t.tongueRings = sp.tongueRings;
    t.tongueSegments = sp.tongueSegments;
    return t;
}

// Skin vertices (the grid, then lower slit copies in lowerCopy()'s order) and their triangles.
void addSkin(FaceTopology& t, std::vector<Eigen::Vector3i>& tris)
{
    const int kEye = t.rowKnot[3], kSto = t.rowKnot[7];
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c) {
            const bool slit = t.lowerCopy(r, c) >= 0;
            t.skin.push_back({ r, c, slit ? +1 : 0 });
        }
    for (int s = -t.sEx + 1; s <= -t.sEn - 1; ++s)
        t.skin.push_back({ kEye, t.mid + s, -1 });
    for (int s = t.sEn + 1; s <= t.sEx - 1; ++s)
        t.skin.push_back({ kEye, t.mid + s, -1 });
    for (int s = -t.sCh + 1; s <= t.sCh - 1; ++s)
        t.skin.push_back({ kSto, t.mid + s, -1 });
    const int nSkin = static_cast<int>(t.skin.size());
    for (int i = t.rows * t.cols; i < nSkin; ++i)
        if (t.lowerCopy(t.skin[i].row, t.skin[i].col) != i)
            fail("buildFaceTopology: slit copy ", i, " misplaced (internal error)");

    for (int r = 0; r + 1 < t.rows; ++r)
        for (int c = 0; c + 1 < t.cols; ++c) {
            // Cells below a slit use the slit's lower copies.
            auto top = [&](int col) {
                const int lower = t.lowerCopy(r, col);
                return lower >= 0 ? lower : t.grid(r, col);
            };
            const int a = top(c), b = top(c + 1), cc = t.grid(r + 1, c), d = t.grid(r + 1, c + 1);
            if (c + 1 > t.mid) { // mirror the diagonal across the midline so faces stay symmetric
                tris.emplace_back(a, cc, d);
                tris.emplace_back(a, d, b);
            } else {
                tris.emplace_back(a, cc, b);
                tris.emplace_back(b, cc, d);
            }
        }
}

// The components (skin, then eyeballs, dental arches and tongue after it), the vertex count
// and the triangle list of the manifest.
void addParts(FaceTopology& t, std::vector<Eigen::Vector3i>& tris)
{
    Manifest& m = t.labels;
    const int nSkin = static_cast<int>(t.skin.size());
    int next = nSkin;
    m.components.push_back({ "skin", 0, nSkin });
    const int eyeCount = 2 + t.eyeRings * t.eyeSegments;
    for (const char* name : { "eye_right", "eye_left" }) {
        addSphere(tris, next, t.eyeRings, t.eyeSegments);
        m.components.push_back({ name, next, next + eyeCount });
        next += eyeCount;
    }
    const int archCount = 2 + t.archSamples * t.archSection;
    for (const char* name : { "teeth_upper", "teeth_lower" }) {
        addTube(tris, next, t.archSamples, t.archSection);
        m.components.push_back({ name, next, next + archCount });
        next += archCount;
    }
    const int tongueCount = 2 + t.tongueRings * t.tongueSegments;
    addSphere(tris, next, t.tongueRings, t.tongueSegments);
    m.components.push_back({ "tongue", next, next + tongueCount });
    next += tongueCount;

    m.vertexCount = next;
    m.topology.resize(static_cast<Eigen::Index>(tris.size()), 3);
    for (size_t i = 0; i < tris.size(); ++i)
        m.topology.row(static_cast<Eigen::Index>(i)) = tris[i].transpose();
}

// Craniofacial landmarks (thesis Table 3.1). Suffix _l is the face's own left (+x).
void labelLandmarks(FaceTopology& t)
{
    Manifest& m = t.labels;
    const int kBrow = t.rowKnot[1], kN = t.rowKnot[2], kEye = t.rowKnot[3], kPrn = t.rowKnot[4], kSn = t.rowKnot[5], kLs = t.rowKnot[6],
              kSto = t.rowKnot[7], kLi = t.rowKnot[8], kPg = t.rowKnot[9], kGn = t.rowKnot[10];
    const int mid = t.mid, sEye = (t.sEn + t.sEx) / 2;
    auto g = [&](int r, int s) { return t.grid(r, mid + s); };
    auto low = [&](int r, int s) { return t.lowerCopy(r, mid + s); };
    auto both = [&](const std::string& name, int r, int s) {
        m.landmarks[name + "_l"] = g(r, s);
        m.landmarks[name + "_r"] = g(r, -s);
    };
    m.landmarks["g"] = g(kBrow, 0);
    m.landmarks["n"] = g(kN, 0);
    m.landmarks["s"] = g(kN + 1, 0);
    m.landmarks["cs1"] = g((kEye + kPrn) / 2, 0);
    m.landmarks["prn"] = g(kPrn, 0);
    m.landmarks["sn"] = g(kSn, 0);
    m.landmarks["ls"] = g(kLs, 0);
    m.landmarks["sto"] = g(kSto, 0);
    m.landmarks["li"] = g(kLi, 0);
    m.landmarks["sl"] = g((kLi + kPg + 1) / 2, 0);
    m.landmarks["pg"] = g(kPg, 0);
    m.landmarks["gn"] = g(kGn, 0);
    both("en", kEye, t.sEn);
    both("ex", kEye, t.sEx);
    both("os", kBrow, sEye);
    both("ps", kEye, sEye);
    m.landmarks["pi_l"] = low(kEye, sEye);
    m.landmarks["pi_r"] = low(kEye, -sEye);
    both("mf", kN, std::max(1, t.sEn - 1));
    both("al", kPrn, t.sEn);
    both("sbal", kSn, std::max(1, t.sEn - 1));
    both("ch", kSto, t.sCh);
    const int sCph = std::max(1, static_cast<int>(std::lround(t.sCh * 0.2)));
    both("cph", kLs, sCph);
    both("obs", kEye + 1, t.mid);
}

// The labelled contours (thesis 4.3.3) and the vertices never used as contour candidates.
void labelContours(FaceTopology& t)
{
    Manifest& m = t.labels;
    const int kBrow = t.rowKnot[1], kEye = t.rowKnot[3], kPrn = t.rowKnot[4], kSn = t.rowKnot[5], kLs = t.rowKnot[6], kSto = t.rowKnot[7],
              kLi = t.rowKnot[8], kGn = t.rowKnot[10];
    auto g = [&](int r, int s) { return t.grid(r, t.mid + s); };
    auto low = [&](int r, int s) { return t.lowerCopy(r, t.mid + s); };
    auto& C = m.contours;
    for (int side : { 1, -1 }) {
        const std::string sfx = side > 0 ? "_l" : "_r";
        std::vector<int>& brow = C["eyebrow" + sfx];
        for (int s = t.sEn; s <= t.sEx + 1; ++s)
            brow.push_back(g(kBrow, side * s));
        std::vector<int>& socket = C["eye_socket" + sfx];
        for (int s = t.sEn; s <= t.sEx; ++s)
            socket.push_back(g(kEye, side * s));
        for (int s = t.sEx - 1; s > t.sEn; --s)
            socket.push_back(low(kEye, side * s));
    }
    auto lipRow = [&](int s, int kOuter) {
        const double x = static_cast<double>(s) / t.sCh;
        return kSto + static_cast<int>(std::lround((kOuter - kSto) * std::sqrt(std::max(0.0, 1 - x * x))));
    };
    for (int s = -t.sCh; s <= t.sCh; ++s) {
        C["lip_upper_outer"].push_back(g(lipRow(s, kLs), s));
        C["lip_lower_outer"].push_back(std::abs(s) == t.sCh ? g(kSto, s) : g(lipRow(s, kLi), s));
        C["lip_upper_inner"].push_back(g(kSto, s));
        C["lip_lower_inner"].push_back(std::abs(s) == t.sCh ? g(kSto, s) : low(kSto, s));
    }
    // Lower outer contour: a row reached by lipRow on the slit row must use the lower copy.
    for (int& v : C["lip_lower_outer"])
        if (t.skin[static_cast<size_t>(v)].row == kSto && t.lowerCopy(kSto, t.skin[static_cast<size_t>(v)].col) >= 0)
            v = t.lowerCopy(kSto, t.skin[static_cast<size_t>(v)].col);
    // Nostrils: a ring of grid vertices on the opening's rim, around its centre (face_frame.h
    // kNostrilAt and kNostrilOut; al is column sEn on the nose's rows) at the footprint's half-axes
    // (kNostrilHalfHeight of the rows from prn to sn, kNostrilHalfWidthOfAl of the columns out to
    // al). Until v12 the ring had about 0.7 of those half-axes (a third of the rows, a quarter of
    // the columns), so on the high and ultra grids it lay inside the footprint and the vestibule
    // carried it 1-11 mm up into the nose (mean 4.9 mm; on the rim now: 0.1 mm, at most 1.3).
    const int rc = kSn - std::max(1, static_cast<int>(std::lround((kSn - kPrn) * detail::kNostrilAt)));
    const int sc = std::max(1, static_cast<int>(std::lround(t.sEn * detail::kNostrilOut)));
    const int dr = std::max(1, static_cast<int>(std::lround((kSn - kPrn) * detail::kNostrilHalfHeight)));
    const int dc = std::max(1, static_cast<int>(std::lround(t.sEn * detail::kNostrilHalfWidthOfAl)));
    for (int side : { 1, -1 }) {
        std::vector<int>& ring = C[side > 0 ? "nostril_l" : "nostril_r"];
        for (int k = 0; k < 8; ++k) {
            const double angle = 2 * M_PI * k / 8;
            const int r = std::clamp(rc + static_cast<int>(std::lround(-dr * std::sin(angle))), kPrn, kSn);
            const int s = std::max(1, sc + static_cast<int>(std::lround(dc * std::cos(angle))));
            const int v = g(r, side * s);
            if (ring.empty() || (ring.back() != v && ring.front() != v))
                ring.push_back(v);
        }
        // Interior of the pit: hidden from almost every view (thesis 4.3.3 excludes such).
        for (int r = rc - dr + 1; r <= rc + dr - 1; ++r)
            for (int s = sc - dc + 1; s <= sc + dc - 1; ++s)
                if (r > kPrn && r < kSn && s >= 1)
                    m.excluded.push_back(g(r, side * s));
    }
    // Under the chin is hidden from the front and the side.
    for (int r = kGn + 2; r < t.rows; ++r)
        for (int s = -t.sCh; s <= t.sCh; ++s)
            m.excluded.push_back(g(r, s));
    std::sort(m.excluded.begin(), m.excluded.end());
    m.excluded.erase(std::unique(m.excluded.begin(), m.excluded.end()), m.excluded.end());
}

// MPEG-4 feature points (thesis 5.2; group.point numbering of ISO/IEC 14496-2 Annex C, with
// the thesis' Table 3.1 assignment of 3.7/3.8/3.11/3.12). Needs the landmarks and contours.
void labelMpeg4(FaceTopology& t)
{
    Manifest& m = t.labels;
    const int kBrow = t.rowKnot[1], kEye = t.rowKnot[3], kPrn = t.rowKnot[4], kSto = t.rowKnot[7];
    const int sEye = (t.sEn + t.sEx) / 2;
    auto g = [&](int r, int s) { return t.grid(r, t.mid + s); };
    auto low = [&](int r, int s) { return t.lowerCopy(r, t.mid + s); };
    const auto& C = m.contours;
    auto& M = m.mpeg4;
    auto& L = m.landmarks;
    labelMpeg4FromLandmarks(m);
    M["2.2"] = g(kSto, 0);
    M["2.3"] = low(kSto, 0);
    M["2.4"] = g(kSto, t.sCh - 1);
    M["2.5"] = g(kSto, -(t.sCh - 1));
    M["2.6"] = g(kSto, t.sCh / 2);
    M["2.7"] = g(kSto, -t.sCh / 2);
    M["2.8"] = low(kSto, t.sCh / 2);
    M["2.9"] = low(kSto, -t.sCh / 2);
    M["4.1"] = g(kBrow, t.sEn);
    M["4.2"] = g(kBrow, -t.sEn);
    M["4.3"] = g(kBrow, sEye);
    M["4.4"] = g(kBrow, -sEye);
    M["4.5"] = g(kBrow, t.sEx + 1);
    M["4.6"] = g(kBrow, -(t.sEx + 1));
    M["5.3"] = g((kEye + kPrn) / 2, t.sEx);
    M["5.4"] = g((kEye + kPrn) / 2, -t.sEx);
    M["8.1"] = L["ls"];
    M["8.2"] = L["li"];
    M["8.3"] = L["ch_l"];
    M["8.4"] = L["ch_r"];
    const auto& upperOuter = C.at("lip_upper_outer");
    const auto& lowerOuter = C.at("lip_lower_outer");
    M["8.5"] = upperOuter[static_cast<size_t>(t.sCh + t.sCh / 2)];
    M["8.6"] = upperOuter[static_cast<size_t>(t.sCh - t.sCh / 2)];
    M["8.7"] = lowerOuter[static_cast<size_t>(t.sCh + t.sCh / 2)];
    M["8.8"] = lowerOuter[static_cast<size_t>(t.sCh - t.sCh / 2)];
    M["8.9"] = L["cph_r"];
    M["8.10"] = L["cph_l"];
    M["9.1"] = L["al_l"];
    M["9.2"] = L["al_r"];
    M["9.3"] = L["prn"];
    M["9.15"] = L["sn"];
    // Tongue (sphere poles are its top and bottom): tip, dorsum centre, left and right borders.
    const Component* tongue = m.component("tongue");
    const int tr = t.tongueRings / 2, ts = t.tongueSegments;
    auto tongueRing = [&](int j) { return tongue->begin + 1 + tr * ts + (j % ts); };
    M["6.1"] = tongueRing(0);
    M["6.2"] = tongue->begin;
    M["6.3"] = tongueRing(ts / 4);
    M["6.4"] = tongueRing(3 * ts / 4);
    // Lower teeth: incisal edge at the midline, and the left canine tip.
    const Component* lowerTeeth = m.component("teeth_lower");
    auto archTop = [&](int i) { return lowerTeeth->begin + 1 + i * t.archSection; };
    M["9.10"] = archTop(t.archSamples / 2);
    M["9.11"] = archTop(t.archSamples / 2 + std::max(1, t.archSamples / 5));
}

} // namespace

FaceTopology buildFaceTopology(Resolution resolution)
{
    FaceTopology t = layout(resolution);
    std::vector<Eigen::Vector3i> tris;
    addSkin(t, tris);
    addParts(t, tris);
    labelLandmarks(t);
    labelContours(t);
    labelMpeg4(t);
    return t;
}

} // namespace facesketch::dataset

// The labelling rules of the ICT import (import_ict_labels.h) on the real ICT Face Model Light;
// skipped visibly when the model is absent (ict_fixtures.h).
#include "dataset/import_ict_labels.h"
#include "core/error.h"
#include "dataset/dataset.h"
#include "dataset/import_ict.h"
#include "ict_fixtures.h"
#include "test_common.h"

#include <cmath>
#include <set>

using namespace facesketch;
using namespace facesketch::dataset;
using test::ictDir;
using test::isEdgePath;
using test::isLoop;

TEST_CASE("import_ict_labels: 10 identities put every landmark on its feature, in mm, with edge-path contours")
{
    REQUIRE_ICT_OR_SKIP();
    test::TempDir dir;
    IctOptions o;
    o.identities = 10;
    o.eyes = o.mouth = true;
    const Manifest m = writeIctDataset(ictDir(), dir / "ict", o);
    const Dataset d = openDataset(dir / "ict");
    REQUIRE(d.manifest.samples.size() == 10);
    REQUIRE(d.manifest.units == "mm");
    const Component& skin = *d.manifest.component("skin");
    REQUIRE(skin.size() == 9409);
    for (const char* c : { "eye_left", "eye_right", "teeth_upper", "teeth_lower", "gums", "tongue" })
        REQUIRE(d.manifest.component(c));
    REQUIRE(d.manifest.mpeg4.size() == 46); // thesis 5.2: 40 skin, 4 tongue, 2 lower teeth
    const Component& tongue = *d.manifest.component("tongue");
    for (const char* p : { "6.1", "6.2", "6.3", "6.4" })
        REQUIRE(tongue.contains(m.mpeg4.at(p)));
    for (const auto& [name, path] : m.contours) {
        INFO(name);
        REQUIRE(isEdgePath(m.topology, path, isLoop(name)));
        REQUIRE(std::set<int>(path.begin(), path.end()).size() == path.size()); // no vertex twice
        for (int v : path)
            REQUIRE(skin.contains(v));
    }
    REQUIRE(m.contours.count("nostril_l"));
    REQUIRE(m.contours.count("nostril_r"));
    // The cavity inside each rim is hidden from contour candidates; the rims themselves are not.
    std::set<int> hiddenSkin;
    for (int v : m.excluded)
        if (skin.contains(v))
            hiddenSkin.insert(v);
    for (const char* ring : { "nostril_l", "nostril_r" })
        for (int v : m.contours.at(ring))
            REQUIRE(!hiddenSkin.count(v));
    const std::set<int> all(m.excluded.begin(), m.excluded.end());
    REQUIRE(all.size() == m.excluded.size());
    const auto& L = m.landmarks;
    std::vector<double> heights;
    for (const Sample& s : d.manifest.samples) {
        const Mesh mesh = loadMesh(d, s.file); // validates: finite, topology
        const Vertices& V = mesh.V;
        INFO(s.name);
        REQUIRE(V.allFinite());
        const double height = (V.row(L.at("n")) - V.row(L.at("gn"))).norm();
        heights.push_back(height);
        REQUIRE(height > 100);
        REQUIRE(height < 140);
        // prn: the most forward skin vertex lies within 3 mm of it. "Forward" is the face's own:
        // real heads are pitched differently, so it is measured along (ex_l - ex_r) x (n - gn).
        const Eigen::RowVector3d across = V.row(L.at("ex_l")) - V.row(L.at("ex_r"));
        const Eigen::RowVector3d up = V.row(L.at("n")) - V.row(L.at("gn"));
        const Eigen::RowVector3d forward = across.cross(up).normalized();
        REQUIRE(forward(2) > 0.9);
        Eigen::Index front = 0;
        (V.middleRows(skin.begin, skin.size()) * forward.transpose()).maxCoeff(&front);
        const double apart = (V.row(front) - V.row(L.at("prn"))).norm();
        // ICT's vertices along the tip are about 3 mm apart, so the bar is 3 mm or one edge at prn.
        double edge = 0;
        for (Eigen::Index f = 0; f < m.topology.rows(); ++f)
            for (int k = 0; k < 3; ++k)
                if (m.topology(f, k) == L.at("prn"))
                    for (int j = 1; j < 3; ++j)
                        edge = std::max(edge, (V.row(L.at("prn")) - V.row(m.topology(f, (k + j) % 3))).norm());
        INFO("prn is " << apart << " mm from the most forward vertex " << front << "; longest edge at prn " << edge);
        REQUIRE(apart < std::max(3.0, 1.05 * edge));
        // ch: the outer lip corners, the lip contour vertices of extreme x.
        for (const char* lip : { "lip_upper_outer", "lip_lower_outer" }) {
            double minX = 1e9, maxX = -1e9;
            for (int v : m.contours.at(lip)) {
                minX = std::min(minX, V(v, 0));
                maxX = std::max(maxX, V(v, 0));
            }
            REQUIRE(V(L.at("ch_l"), 0) > maxX - 1);
            REQUIRE(V(L.at("ch_r"), 0) < minX + 1);
        }
        // Sides and order of the eye corners; face's left is +x.
        REQUIRE(V(L.at("ex_l"), 0) > V(L.at("en_l"), 0));
        REQUIRE(V(L.at("en_l"), 0) > 0);
        REQUIRE(V(L.at("en_r"), 0) < 0);
        REQUIRE(V(L.at("ex_r"), 0) < V(L.at("en_r"), 0));
        // Plausible sizes (Farkas' adult norms give about 35 mm nose width, 90 mm biocular width).
        const double nose = V(L.at("al_l"), 0) - V(L.at("al_r"), 0);
        const double eyes = V(L.at("ex_l"), 0) - V(L.at("ex_r"), 0);
        REQUIRE(nose > 25);
        REQUIRE(nose < 50);
        REQUIRE(eyes > 75);
        REQUIRE(eyes < 110);
        // Profile order along the midline.
        REQUIRE(V(L.at("g"), 1) > V(L.at("n"), 1));
        REQUIRE(V(L.at("prn"), 1) > V(L.at("sn"), 1));
        REQUIRE(V(L.at("sn"), 1) > V(L.at("ls"), 1));
        REQUIRE(V(L.at("ls"), 1) > V(L.at("sto"), 1));
        REQUIRE(V(L.at("sto"), 1) > V(L.at("li"), 1));
        REQUIRE(V(L.at("li"), 1) > V(L.at("sl"), 1));
        REQUIRE(V(L.at("sl"), 1) > V(L.at("pg"), 1));
        REQUIRE(V(L.at("pg"), 1) > V(L.at("gn"), 1));
        REQUIRE(V(L.at("ps_l"), 1) > V(L.at("pi_l"), 1));
        REQUIRE(V(L.at("os_l"), 1) > V(L.at("ps_l"), 1));
        // Nostril rings: each around its own nostril, below prn and beside sn, medial to its sbal.
        // ICT's nostril openings run up to about 21 mm forward from sbal (250 identities, seed 1).
        for (int side : { 1, -1 }) {
            const std::string sfx = side > 0 ? "_l" : "_r";
            const std::vector<int>& ring = m.contours.at("nostril" + sfx);
            Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
            double far = 0;
            for (int v : ring) {
                centre += V.row(v) / static_cast<double>(ring.size());
                far = std::max(far, (V.row(v) - V.row(L.at("sbal" + sfx))).norm());
            }
            INFO("nostril" << sfx << ": " << ring.size() << " vertices, centroid (" << centre << "), farthest " << far << " mm from sbal");
            REQUIRE(ring.size() >= 12);
            REQUIRE(side * centre(0) > 2);
            REQUIRE(side * centre(0) < side * V(L.at("sbal" + sfx), 0));
            REQUIRE(centre(1) > V(L.at("sn"), 1));
            REQUIRE(centre(1) < V(L.at("prn"), 1));
            REQUIRE(far < 25);
            int hiddenNear = 0;
            for (int v : hiddenSkin)
                if ((V.row(v) - V.row(L.at("sbal" + sfx))).norm() < 25 && side * V(v, 0) > 0)
                    ++hiddenNear;
            REQUIRE(hiddenNear >= 10);
        }
        for (int v : hiddenSkin) // only the nostril cavities are hidden skin
            REQUIRE(std::min((V.row(v) - V.row(L.at("sbal_l"))).norm(), (V.row(v) - V.row(L.at("sbal_r"))).norm()) < 25);
        // Tongue: 6.1 the most forward tongue vertex, 6.2 on the midline behind it and above the
        // borders, 6.3 (left) at +x and 6.4 (right) at -x.
        const Eigen::Index first = tongue.begin;
        Eigen::Index ahead = 0;
        V.middleRows(first, tongue.size()).col(2).maxCoeff(&ahead);
        const double tipBehind = V(first + ahead, 2) - V(m.mpeg4.at("6.1"), 2);
        INFO("6.1 is " << tipBehind << " mm behind the most forward tongue vertex");
        REQUIRE(tipBehind < 1);
        REQUIRE(std::abs(V(m.mpeg4.at("6.1"), 0)) < 2);
        REQUIRE(std::abs(V(m.mpeg4.at("6.2"), 0)) < 2);
        REQUIRE(V(m.mpeg4.at("6.1"), 2) - V(m.mpeg4.at("6.2"), 2) > 15);
        REQUIRE(V(m.mpeg4.at("6.3"), 0) > 15);
        REQUIRE(V(m.mpeg4.at("6.4"), 0) < -15);
        for (const char* border : { "6.3", "6.4" })
            REQUIRE(V(m.mpeg4.at("6.2"), 1) > V(m.mpeg4.at(border), 1));
    }
    // Distinct identities.
    REQUIRE(*std::max_element(heights.begin(), heights.end()) - *std::min_element(heights.begin(), heights.end()) > 1);
}

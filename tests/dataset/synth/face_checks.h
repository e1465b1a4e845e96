#pragma once
// Mesh checks shared by the synthetic-face tests (face_shape.cpp, pose_recipes.cpp).

#include "dataset/mesh_quality.h"
#include "dataset/synth/face_generator.h"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

namespace facesketch::dataset::checks {

// Degenerate, flipped, folded and intersecting triangles.
// Flipped, for a neutral face (`reference` null): the skin is star-shaped about the origin
// (face_generator.h) so no skin triangle may face it, except in the nostrils: each vestibule is a
// pocket going up into the nose from its underside (face_shape.cpp), and a few triangles of its
// front wall face back, towards the origin. There, on the underside between the prn and sn rows and
// within the alar columns, an inverted triangle still shows, as a fold against its neighbours
// (foldedEdges below); eyeballs and tongue face away from their
// centroids; the teeth keep the orientation of `teethReference` (any face of the topology).
// For a pose, `reference` is the same face with only the pose's jaw rotation, and no
// triangle may turn more than 90 degrees from it: the rigid jaw rotation is factored out, and
// what remains (lids, brows, lips sliding) must never turn a triangle over.
inline void requireClean(
    const FaceTopology& t, const Mesh& mesh, const Vertices& teethReference, const std::string& what, const Vertices* reference = nullptr)
{
    INFO(what);
    const auto degenerate = degenerateTriangles(mesh);
    if (!degenerate.empty())
        UNSCOPED_INFO("first degenerate triangle " << degenerate[0]);
    REQUIRE(degenerate.empty());
    for (const Component& c : t.labels.components) {
        std::vector<int> tris;
        for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
            if (c.contains(mesh.F(f, 0)))
                tris.push_back(static_cast<int>(f));
        std::vector<int> flipped;
        if (reference) {
            for (int f : flippedTriangles(mesh, *reference))
                if (c.contains(mesh.F(f, 0)))
                    flipped.push_back(f);
        } else if (c.name == "skin") {
            auto onNoseUnderside = [&](int v) {
                const SkinVertex& sv = t.skin[static_cast<size_t>(v - c.begin)];
                return sv.row >= t.rowKnot[4] && sv.row <= t.rowKnot[5] && std::abs(sv.col - t.mid) <= t.sEn;
            };
            for (int f : trianglesFacingCentre(mesh, Eigen::Vector3d::Zero(), tris))
                if (!(onNoseUnderside(mesh.F(f, 0)) && onNoseUnderside(mesh.F(f, 1)) && onNoseUnderside(mesh.F(f, 2))))
                    flipped.push_back(f);
        } else if (c.name.rfind("teeth", 0) == 0) {
            for (int f : flippedTriangles(mesh, teethReference))
                if (c.contains(mesh.F(f, 0)))
                    flipped.push_back(f);
        } else
            flipped = trianglesFacingCentre(mesh, mesh.V.middleRows(c.begin, c.size()).colwise().mean().transpose(), tris);
        if (!flipped.empty())
            UNSCOPED_INFO("first flipped triangle " << flipped[0] << " in " << c.name);
        REQUIRE(flipped.empty());
    }
    const auto folds = foldedEdges(mesh);
    if (!folds.empty())
        UNSCOPED_INFO("first fold between triangles " << folds[0].first << " and " << folds[0].second);
    REQUIRE(folds.empty());
    const auto hits = selfIntersections(mesh);
    if (!hits.empty())
        UNSCOPED_INFO("first intersection between triangles " << hits[0].first << " and " << hits[0].second);
    REQUIRE(hits.empty());
}

} // namespace facesketch::dataset::checks

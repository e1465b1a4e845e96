#include "contours/region_candidates.h"

#include "core/error.h"

#include <algorithm>

namespace facesketch {

RegionCandidates::RegionCandidates(const Triangles& F, Eigen::Index vertexCount, std::vector<std::uint32_t> flags)
    : F_(F)
    , vertexCount_(vertexCount)
    , flags_(std::move(flags))
    , rings_(buildNeighbours(buildWedges(F, vertexCount)))
{
    if (!flags_.empty() && static_cast<Eigen::Index>(flags_.size()) != vertexCount)
        fail("RegionCandidates: ", flags_.size(), " vertex flags for ", vertexCount, " vertices");
    faceOffsets_.assign(static_cast<size_t>(vertexCount) + 1, 0);
    for (Eigen::Index t = 0; t < F.rows(); ++t)
        for (int k = 0; k < 3; ++k)
            ++faceOffsets_[static_cast<size_t>(F(t, k)) + 1];
    for (size_t v = 0; v < static_cast<size_t>(vertexCount); ++v)
        faceOffsets_[v + 1] += faceOffsets_[v];
    faces_.resize(faceOffsets_.back());
    std::vector<std::uint32_t> next(faceOffsets_.begin(), faceOffsets_.end() - 1);
    for (Eigen::Index t = 0; t < F.rows(); ++t)
        for (int k = 0; k < 3; ++k)
            faces_[next[static_cast<size_t>(F(t, k))]++] = static_cast<std::uint32_t>(t);
}

std::vector<Candidate> RegionCandidates::build(const Mesh& mesh, const Camera& camera, const ContourParams& params)
{
    if (mesh.V.rows() != vertexCount_ || mesh.F.rows() != F_.rows())
        fail("RegionCandidates: a mesh of ", mesh.V.rows(), " vertices and ", mesh.F.rows(), " triangles for a topology of ", vertexCount_,
            " and ", F_.rows());
    validateMesh(mesh, "RegionCandidates");
    const auto nv = static_cast<size_t>(vertexCount_);
    lastVertices_ = lastTriangles_ = 0;

    // The vertices inside the rectangle and sphere (the only ones that can be candidates),
    // grown by two rings, or three for rtsc's filter, which reads the one-ring's derivative.
    const char reach = params.suggestiveFilter == SuggestiveFilter::RtscCrossing ? 3 : 2;
    std::vector<char> hops(nv, 4);
    std::vector<std::uint32_t> frontier;
    const glm::dvec3 centre(params.sphere[0], params.sphere[1], params.sphere[2]);
    for (size_t v = 0; v < nv; ++v) {
        const glm::dvec3 p(mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2));
        const glm::dvec3 s = camera.project(p);
        if (s.x < params.rect[0] || s.x > params.rect[2] || s.y < params.rect[1] || s.y > params.rect[3]
            || glm::length(p - centre) > params.sphere[3])
            continue;
        hops[v] = 0;
        frontier.push_back(static_cast<std::uint32_t>(v));
    }
    if (frontier.empty())
        return {};
    for (char h = 1; h <= reach; ++h) {
        std::vector<std::uint32_t> grown;
        for (const std::uint32_t v : frontier)
            for (std::uint32_t k = rings_.offsets[v]; k < rings_.offsets[v + 1]; ++k)
                if (const std::uint32_t u = rings_.vertices[k]; hops[u] > h) {
                    hops[u] = h;
                    grown.push_back(u);
                }
        frontier.swap(grown);
    }

    // Every triangle at those vertices, in F's order, and their vertices in ascending order.
    std::vector<char> takeFace(static_cast<size_t>(F_.rows()), 0), takeVertex(nv, 0);
    for (size_t v = 0; v < nv; ++v)
        if (hops[v] <= reach)
            for (std::uint32_t k = faceOffsets_[v]; k < faceOffsets_[v + 1]; ++k)
                takeFace[faces_[k]] = 1;
    std::vector<Eigen::Index> triangles;
    for (Eigen::Index t = 0; t < F_.rows(); ++t)
        if (takeFace[static_cast<size_t>(t)]) {
            triangles.push_back(t);
            for (int k = 0; k < 3; ++k)
                takeVertex[static_cast<size_t>(F_(t, k))] = 1;
        }
    std::vector<int> local(nv, -1);
    std::vector<std::uint32_t> global;
    for (size_t v = 0; v < nv; ++v)
        if (takeVertex[v]) {
            local[v] = static_cast<int>(global.size());
            global.push_back(static_cast<std::uint32_t>(v));
        }
    Mesh region;
    region.V.resize(static_cast<Eigen::Index>(global.size()), 3);
    std::vector<std::uint32_t> flags;
    for (size_t i = 0; i < global.size(); ++i) {
        region.V.row(static_cast<Eigen::Index>(i)) = mesh.V.row(global[i]);
        if (!flags_.empty())
            flags.push_back(flags_[global[i]]);
    }
    region.F.resize(static_cast<Eigen::Index>(triangles.size()), 3);
    for (size_t i = 0; i < triangles.size(); ++i)
        for (int k = 0; k < 3; ++k)
            region.F(static_cast<Eigen::Index>(i), k) = local[static_cast<size_t>(F_(triangles[i], k))];
    lastVertices_ = region.V.rows();
    lastTriangles_ = region.F.rows();

    std::vector<Candidate> out = contourCandidates({ region }, { estimateCurvature(region) }, flags, camera, params);
    for (Candidate& c : out)
        c.vertex = global[c.vertex];
    return out;
}

} // namespace facesketch

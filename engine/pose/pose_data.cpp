#include "pose/pose_data.h"

#include "core/error.h"
#include "core/parallel.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

namespace facesketch::pose {

namespace {

std::optional<std::pair<int, int>> parseFdp(const std::string& name)
{
    const auto dot = name.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == name.size())
        return std::nullopt;
    int group = 0, point = 0;
    const char* first = name.data();
    const char* mid = first + dot;
    const char* last = first + name.size();
    const auto a = std::from_chars(first, mid, group);
    const auto b = std::from_chars(mid + 1, last, point);
    if (a.ec != std::errc() || a.ptr != mid || b.ec != std::errc() || b.ptr != last)
        return std::nullopt;
    return std::pair { group, point };
}

} // namespace

bool fdpLess(const std::string& a, const std::string& b)
{
    const auto pa = parseFdp(a), pb = parseFdp(b);
    if (pa && pb)
        return *pa < *pb;
    if (pa != pb) // exactly one parses: parsed names first
        return pa.has_value();
    return a < b;
}

bool isSketchable(const std::string& fdp)
{
    const auto p = parseFdp(fdp);
    if (!p)
        return false;
    const auto [group, point] = *p;
    if (group == 6)
        return false;
    if (group == 9 && (point == 10 || point == 11))
        return false;
    if (group == 2 && point >= 2 && point <= 9)
        return false;
    return true;
}

int FeaturePoints::index(const std::string& name) const
{
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

Eigen::VectorXd FeaturePoints::gather(const Vertices& V) const
{
    Eigen::VectorXd out(3 * size());
    for (Eigen::Index i = 0; i < size(); ++i) {
        const int v = vertices[static_cast<size_t>(i)];
        if (v < 0 || v >= V.rows())
            fail("feature point ", names[static_cast<size_t>(i)], ": vertex ", v, " outside a face of ", V.rows(), " vertices");
        out.segment<3>(3 * i) = V.row(v).transpose();
    }
    return out;
}

Eigen::VectorXd FeaturePoints::gatherFlat(const Eigen::Ref<const Eigen::VectorXd>& face) const
{
    if (face.size() % 3 != 0)
        fail("a face of ", face.size(), " coordinates (not a multiple of 3)");
    Eigen::VectorXd out(3 * size());
    const Eigen::Index n = face.size() / 3;
    for (Eigen::Index i = 0; i < size(); ++i) {
        const int v = vertices[static_cast<size_t>(i)];
        if (v < 0 || v >= n)
            fail("feature point ", names[static_cast<size_t>(i)], ": vertex ", v, " outside a face of ", n, " vertices");
        out.segment<3>(3 * i) = face.segment<3>(3 * v);
    }
    return out;
}

FeaturePoints featurePoints(const dataset::Manifest& manifest, const std::string& where)
{
    std::vector<std::pair<std::string, int>> labels(manifest.mpeg4.begin(), manifest.mpeg4.end());
    std::sort(labels.begin(), labels.end(), [](const auto& a, const auto& b) { return fdpLess(a.first, b.first); });
    if (labels.size() < 4)
        fail(where, ": mpeg4: ", labels.size(), " feature points, posing needs at least 4");
    FeaturePoints fps;
    for (const auto& [name, vertex] : labels) {
        fps.names.push_back(name);
        fps.vertices.push_back(vertex);
    }
    return fps;
}

int PoseSet::poseIndex(const std::string& name) const
{
    const auto it = std::find(poseNames.begin(), poseNames.end(), name);
    return it == poseNames.end() ? -1 : static_cast<int>(it - poseNames.begin());
}

PoseSet loadPoseSet(const dataset::Dataset& dataset, const std::vector<dataset::Role>& roles)
{
    const dataset::Manifest& m = dataset.manifest;
    const std::string where = dataset.folder.string();
    if (m.units != "mm")
        fail(where, ": units are '", m.units, "', posing needs a dataset in mm");

    // Poses of each identity, in manifest order.
    std::map<std::string, std::vector<const dataset::Pose*>> byIdentity;
    for (const dataset::Pose& p : m.poses)
        byIdentity[p.identity].push_back(&p);

    PoseSet set;
    set.fps = featurePoints(m, where);
    set.vertexCount = m.vertexCount;
    set.topology = m.topology;
    std::vector<const dataset::Sample*> samples;
    for (const dataset::Sample& s : m.samples) {
        if (std::find(roles.begin(), roles.end(), s.role) == roles.end() || !byIdentity.count(s.name))
            continue;
        samples.push_back(&s);
    }
    if (samples.empty())
        fail(where, ": no identity with poses has the role(s) asked for (", roles.size(), " roles); make one with --poses");
    for (const dataset::Pose* p : byIdentity[samples.front()->name])
        set.poseNames.push_back(p->name);

    const auto I = static_cast<Eigen::Index>(samples.size());
    const Eigen::Index P = set.poseCount();
    const Eigen::Index d = 3 * static_cast<Eigen::Index>(m.vertexCount);
    set.neutrals.resize(I, d);
    set.meshDisplacements.resize(I * P, d);
    set.fpDisplacements.resize(I * P, 3 * set.fps.size());
    for (const dataset::Sample* s : samples)
        set.identities.push_back({ s->name, s->role });
    // Identities load on all threads, each into its own rows; a failure is reported as when they
    // loaded in turn (parallelFor rethrows the lowest failing index's error).
    parallelFor(static_cast<int>(I), 0, [&](int i) {
        const dataset::Sample& s = *samples[static_cast<size_t>(i)];
        const Mesh neutral = dataset::loadMesh(dataset, s.file);
        validateMesh(neutral, (dataset.folder / s.file).string());
        set.neutrals.row(i) = asVector(neutral.V).transpose();
        const Eigen::VectorXd neutralFps = set.fps.gather(neutral.V);

        const auto& poses = byIdentity.at(s.name);
        if (static_cast<Eigen::Index>(poses.size()) != P)
            fail(where, ": identity '", s.name, "' has ", poses.size(), " poses, '", samples.front()->name, "' has ", P);
        for (Eigen::Index p = 0; p < P; ++p) {
            const std::string& name = set.poseNames[static_cast<size_t>(p)];
            const auto it = std::find_if(poses.begin(), poses.end(), [&](const dataset::Pose* q) { return q->name == name; });
            if (it == poses.end())
                fail(where, ": identity '", s.name, "' has no pose '", name, "'");
            const Mesh posed = dataset::loadMesh(dataset, (*it)->file);
            validateMesh(posed, (dataset.folder / (*it)->file).string());
            set.meshDisplacements.row(set.row(i, p)) = (asVector(posed.V) - asVector(neutral.V)).transpose();
            set.fpDisplacements.row(set.row(i, p)) = (set.fps.gather(posed.V) - neutralFps).transpose();
        }
    });
    return set;
}

PoseSet selectRole(const PoseSet& set, dataset::Role role)
{
    PoseSet out;
    out.fps = set.fps;
    out.vertexCount = set.vertexCount;
    out.topology = set.topology;
    out.poseNames = set.poseNames;
    std::vector<Eigen::Index> keep;
    for (Eigen::Index i = 0; i < set.identityCount(); ++i)
        if (set.identities[static_cast<size_t>(i)].role == role)
            keep.push_back(i);
    const auto I = static_cast<Eigen::Index>(keep.size());
    const Eigen::Index P = set.poseCount();
    out.neutrals.resize(I, set.neutrals.cols());
    out.meshDisplacements.resize(I * P, set.meshDisplacements.cols());
    out.fpDisplacements.resize(I * P, set.fpDisplacements.cols());
    for (Eigen::Index j = 0; j < I; ++j) {
        const Eigen::Index i = keep[static_cast<size_t>(j)];
        out.identities.push_back(set.identities[static_cast<size_t>(i)]);
        out.neutrals.row(j) = set.neutrals.row(i);
        out.meshDisplacements.middleRows(j * P, P) = set.meshDisplacements.middleRows(i * P, P);
        out.fpDisplacements.middleRows(j * P, P) = set.fpDisplacements.middleRows(i * P, P);
    }
    return out;
}

} // namespace facesketch::pose

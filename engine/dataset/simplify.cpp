// Shared-topology simplification of a dataset (simplify.h).
//
// This work is based on:
// Michael Garland and Paul S. Heckbert. Surface simplification using quadric error metrics. 1997
// (through meshoptimizer's meshopt_simplify, Arseny Kapoulkine, https://github.com/zeux/meshoptimizer).
#include "dataset/simplify.h"

#include "core/error.h"
#include "dataset/dataset.h"
#include "io/mesh_io.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <set>

namespace facesketch::dataset {

namespace fs = std::filesystem;

namespace {

std::vector<int> lockedVertices(const Manifest& m)
{
    std::set<int> locked;
    for (const auto& [name, v] : m.landmarks)
        locked.insert(v);
    for (const auto& [name, v] : m.mpeg4)
        locked.insert(v);
    for (const auto& [name, path] : m.contours)
        locked.insert(path.begin(), path.end());
    return { locked.begin(), locked.end() };
}

// Runs meshopt_simplify aiming at `targetIndices`; returns the kept index buffer.
std::vector<unsigned> runSimplifier(
    const std::vector<float>& positions, size_t vertexCount, const std::vector<unsigned>& indices, size_t targetIndices)
{
    std::vector<unsigned> out(indices.size());
    // target_error 1 (the whole extent): the triangle budget, not the error, decides where to stop.
    const size_t count = meshopt_simplify(
        out.data(), indices.data(), indices.size(), positions.data(), vertexCount, 3 * sizeof(float), targetIndices, 1.0f, 0, nullptr);
    out.resize(count);
    return out;
}

size_t usedVertices(const std::vector<unsigned>& indices, size_t vertexCount)
{
    std::vector<char> used(vertexCount, 0);
    size_t n = 0;
    for (unsigned i : indices)
        if (!used[i]) {
            used[i] = 1;
            ++n;
        }
    return n;
}

} // namespace

Simplification simplifyTopology(const Vertices& reference, const Manifest& m, int targetVertices)
{
    if (targetVertices < 4)
        fail("--vertices ", targetVertices, ": need at least 4 vertices");
    if (reference.rows() != m.vertexCount)
        fail("simplify: reference mesh has ", reference.rows(), " vertices, the manifest has ", m.vertexCount);
    const std::vector<int> locked = lockedVertices(m);
    const size_t n = static_cast<size_t>(m.vertexCount);

    // Positions with two coincident copies of every locked vertex appended (see simplify.h).
    std::vector<float> positions(3 * (n + 2 * locked.size()));
    for (size_t v = 0; v < n; ++v)
        for (int k = 0; k < 3; ++k)
            positions[3 * v + k] = static_cast<float>(reference(static_cast<Eigen::Index>(v), k));
    for (size_t i = 0; i < locked.size(); ++i)
        for (size_t copy = 0; copy < 2; ++copy)
            for (int k = 0; k < 3; ++k)
                positions[3 * (n + 2 * i + copy) + k] = positions[3 * static_cast<size_t>(locked[i]) + k];
    const size_t total = positions.size() / 3;

    std::vector<unsigned> indices(static_cast<size_t>(m.topology.size()));
    for (Eigen::Index f = 0; f < m.topology.rows(); ++f)
        for (int k = 0; k < 3; ++k)
            indices[static_cast<size_t>(3 * f + k)] = static_cast<unsigned>(m.topology(f, k));
    const size_t have = usedVertices(indices, total);

    std::vector<unsigned> best = indices;
    if (static_cast<size_t>(targetVertices) < have) {
        // The vertex count follows the triangle budget roughly linearly; a few secant steps on
        // the budget bring it close to the target.
        double ratio = static_cast<double>(indices.size()) / static_cast<double>(have);
        size_t bestMiss = have - static_cast<size_t>(targetVertices);
        for (int step = 0; step < 6; ++step) {
            const size_t budget = std::max<size_t>(3, static_cast<size_t>(ratio * targetVertices) / 3 * 3);
            std::vector<unsigned> out = runSimplifier(positions, total, indices, budget);
            const size_t got = usedVertices(out, total);
            const size_t miss = got > static_cast<size_t>(targetVertices) ? got - targetVertices : targetVertices - got;
            if (miss < bestMiss) {
                bestMiss = miss;
                best = std::move(out);
            }
            if (miss * 50 <= static_cast<size_t>(targetVertices) || got == 0)
                break; // within 2%
            ratio *= static_cast<double>(targetVertices) / static_cast<double>(got);
        }
    }

    std::vector<int> newIndex(n, -1);
    for (unsigned i : best)
        if (i >= n)
            fail("simplify: meshoptimizer returned a lock copy (internal error)");
        else
            newIndex[i] = 0;
    Simplification s;
    for (size_t v = 0; v < n; ++v)
        if (newIndex[v] == 0) {
            newIndex[v] = static_cast<int>(s.kept.size());
            s.kept.push_back(static_cast<int>(v));
        }
    for (int v : locked)
        if (newIndex[static_cast<size_t>(v)] < 0)
            fail("simplify: labelled vertex ", v, " was removed (it is used by no triangle, or meshoptimizer ignored its lock)");
    s.topology.resize(static_cast<Eigen::Index>(best.size() / 3), 3);
    for (size_t i = 0; i < best.size(); ++i)
        s.topology(static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3)) = newIndex[best[i]];
    return s;
}

Manifest simplifyManifest(const Manifest& m, const Simplification& s)
{
    std::vector<int> newIndex(static_cast<size_t>(m.vertexCount), -1);
    for (size_t i = 0; i < s.kept.size(); ++i)
        newIndex[static_cast<size_t>(s.kept[i])] = static_cast<int>(i);
    auto renumber = [&](int v, const std::string& what) {
        const int out = newIndex[static_cast<size_t>(v)];
        if (out < 0)
            fail("simplify: ", what, ": vertex ", v, " was not kept");
        return out;
    };
    // First new index whose old index is >= `old`.
    auto lower = [&](int old) { return static_cast<int>(std::lower_bound(s.kept.begin(), s.kept.end(), old) - s.kept.begin()); };

    Manifest out = m;
    out.vertexCount = static_cast<int>(s.kept.size());
    out.topology = s.topology;
    out.components.clear();
    for (const Component& c : m.components) {
        const Component n { c.name, lower(c.begin), lower(c.end) };
        if (n.size() > 0)
            out.components.push_back(n);
        else if (c.name == "skin")
            fail("simplify: the skin lost all its vertices");
    }
    for (auto& [name, v] : out.landmarks)
        v = renumber(v, "landmarks." + name);
    for (auto& [name, v] : out.mpeg4)
        v = renumber(v, "mpeg4." + name);
    for (auto& [name, path] : out.contours)
        for (int& v : path)
            v = renumber(v, "contours." + name);
    out.excluded.clear();
    for (int v : m.excluded)
        if (newIndex[static_cast<size_t>(v)] >= 0)
            out.excluded.push_back(newIndex[static_cast<size_t>(v)]);
    return out;
}

Vertices keepVertices(const Vertices& V, const Simplification& s)
{
    Vertices out(static_cast<Eigen::Index>(s.kept.size()), 3);
    for (size_t i = 0; i < s.kept.size(); ++i)
        out.row(static_cast<Eigen::Index>(i)) = V.row(s.kept[i]);
    return out;
}

int simplifyDataset(const fs::path& input, const fs::path& output, int targetVertices)
{
    const Dataset in = openDataset(input);
    const Manifest& m = in.manifest;
    if (m.samples.empty())
        fail(input.string(), ": no samples to simplify");
    Vertices mean = Vertices::Zero(m.vertexCount, 3);
    for (const Sample& sample : m.samples)
        mean += loadMesh(in, sample.file).V;
    mean /= static_cast<double>(m.samples.size());
    const Simplification s = simplifyTopology(mean, m, targetVertices);
    const Manifest out = simplifyManifest(m, s);
    writeDataset(output, out, [&](const fs::path& tmp) {
        auto copy = [&](const fs::path& file) {
            fs::create_directories((tmp / file).parent_path());
            writePly(tmp / file, Mesh { keepVertices(loadMesh(in, file).V, s), s.topology });
        };
        for (const Sample& sample : m.samples)
            copy(sample.file);
        for (const Pose& pose : m.poses)
            copy(pose.file);
    });
    return out.vertexCount;
}

} // namespace facesketch::dataset

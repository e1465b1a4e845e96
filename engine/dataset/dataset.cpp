#include "dataset/dataset.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "io/mesh_io.h"

#include <algorithm>
#include <random>
#include <unistd.h>

namespace facesketch::dataset {

namespace fs = std::filesystem;

namespace {

// validateManifest already refuses absolute names and "..": this also refuses a symbolic link
// (of the file or of a folder on its way) that leads out of the dataset folder.
void checkInside(const fs::path& folder, const fs::path& file, const std::string& where, const std::string& field)
{
    std::error_code ec;
    const fs::path root = fs::weakly_canonical(folder, ec);
    const fs::path target = ec ? fs::path() : fs::weakly_canonical(folder / file, ec);
    if (ec)
        fail(where, ": ", field, ": '", file.string(), "': ", ec.message());
    const auto [end, ignored] = std::mismatch(root.begin(), root.end(), target.begin(), target.end());
    if (end != root.end())
        fail(where, ": ", field, ": '", file.string(), "' leads outside the dataset folder (to ", target.string(), ")");
}

void checkFilesExist(const fs::path& folder, const Manifest& m, const std::string& where)
{
    for (size_t i = 0; i < m.samples.size(); ++i) {
        const std::string field = cat("samples[", i, "].file");
        if (!fs::is_regular_file(folder / m.samples[i].file))
            fail(where, ": ", field, ": '", m.samples[i].file.string(), "' does not exist");
        checkInside(folder, m.samples[i].file, where, field);
    }
    for (size_t i = 0; i < m.poses.size(); ++i) {
        const std::string field = cat("poses[", i, "].file");
        if (!fs::is_regular_file(folder / m.poses[i].file))
            fail(where, ": ", field, ": '", m.poses[i].file.string(), "' does not exist");
        checkInside(folder, m.poses[i].file, where, field);
    }
}

} // namespace

Dataset openDataset(const fs::path& folder)
{
    if (!fs::is_directory(folder))
        fail(folder.string(), ": not a folder");
    const fs::path manifestPath = folder / "manifest.json";
    if (!fs::is_regular_file(manifestPath))
        fail(folder.string(), ": no manifest.json (not a dataset folder)");
    Dataset d { folder, readManifest(manifestPath) };
    checkFilesExist(folder, d.manifest, manifestPath.string());
    return d;
}

Mesh loadMesh(const Dataset& dataset, const fs::path& file)
{
    const fs::path path = dataset.folder / file;
    Mesh mesh = readMesh(path);
    const Manifest& m = dataset.manifest;
    if (mesh.vertexCount() != m.vertexCount)
        fail(path.string(), ": has ", mesh.vertexCount(), " vertices, the manifest's topology has ", m.vertexCount);
    if (mesh.triangleCount() != m.topology.rows())
        fail(path.string(), ": has ", mesh.triangleCount(), " triangles, the manifest's topology has ", m.topology.rows());
    for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f)
        if (mesh.F.row(f) != m.topology.row(f))
            fail(path.string(), ": triangle ", f, " (", mesh.F(f, 0), ", ", mesh.F(f, 1), ", ", mesh.F(f, 2),
                ") differs from the manifest's topology[", f, "]");
    return mesh;
}

Eigen::RowVectorXd flatten(const Vertices& V)
{
    return asVector(V).transpose();
}

Vertices unflatten(const Eigen::Ref<const Eigen::RowVectorXd>& row)
{
    const Eigen::VectorXd column = row.transpose();
    return asVertices(column); // throws Error unless the size is a multiple of 3
}

Eigen::MatrixXd loadShapes(const Dataset& dataset, Role role, const std::string& componentName)
{
    const Manifest& m = dataset.manifest;
    int begin = 0, end = m.vertexCount;
    if (!componentName.empty()) {
        const Component* c = m.component(componentName);
        if (!c)
            fail(dataset.folder.string(), ": no component '", componentName, "'");
        begin = c->begin;
        end = c->end;
    }
    const auto samples = m.samplesWithRole(role);
    Eigen::MatrixXd shapes(static_cast<Eigen::Index>(samples.size()), 3 * (end - begin));
    // The meshes load on all threads, each into its own row; a bad file is reported as when they
    // loaded in turn (parallelFor rethrows the lowest failing index's error).
    parallelFor(static_cast<int>(samples.size()), 0, [&](int i) {
        const Mesh mesh = loadMesh(dataset, samples[static_cast<size_t>(i)]->file);
        shapes.row(i) = flatten(mesh.V.middleRows(begin, end - begin));
    });
    return shapes;
}

void writeDataset(const fs::path& folderIn, const Manifest& manifest, const std::function<void(const fs::path&)>& fill)
{
    const fs::path folder = folderIn.has_filename() ? folderIn : folderIn.parent_path();
    const std::string where = folder.string();
    validateManifest(manifest, (folder / "manifest.json").string());
    const fs::path parent = folder.has_parent_path() ? folder.parent_path() : fs::path(".");
    if (!fs::is_directory(parent))
        fail(where, ": parent folder ", parent.string(), " does not exist");
    if (fs::exists(folder)) {
        if (!fs::is_directory(folder))
            fail(where, ": exists and is not a folder");
        if (!fs::is_empty(folder) && !fs::exists(folder / "manifest.json"))
            fail(where, ": exists, is not empty and is not a dataset (no manifest.json); not replacing it");
    }

    std::mt19937_64 rng(std::random_device {}() ^ static_cast<unsigned>(getpid()));
    const std::string tag = cat(getpid(), "-", rng() % 1000000007u);
    const fs::path tmp = parent / cat(".", folder.filename().string(), ".tmp-", tag);
    const fs::path old = parent / cat(".", folder.filename().string(), ".old-", tag);
    try {
        fs::create_directory(tmp);
        {
            const StagingFolder staging(tmp);
            fill(tmp);
            writeManifest(tmp / "manifest.json", manifest);
        }
        checkFilesExist(tmp, manifest, (folder / "manifest.json").string());
        // Every file of the new folder reaches the disk before its name is published.
        syncFilesystem(tmp);
        if (fs::exists(folder) && exchangePaths(tmp, folder)) {
            // One atomic step: `folder` names the whole old dataset, then the whole new one.
            syncPath(parent);
            fs::remove_all(tmp); // now the old dataset
        } else if (fs::exists(folder)) {
            // A file system without RENAME_EXCHANGE: rename() cannot replace a non-empty
            // folder, so the old one steps aside first (a crash between the two renames leaves
            // it at `.NAME.old-*`) and is deleted only after the new one is in place.
            fs::rename(folder, old);
            try {
                fs::rename(tmp, folder);
            } catch (...) {
                fs::rename(old, folder);
                throw;
            }
            syncPath(parent);
            fs::remove_all(old);
        } else {
            fs::rename(tmp, folder);
            syncPath(parent);
        }
    } catch (const fs::filesystem_error& e) {
        std::error_code ignored;
        fs::remove_all(tmp, ignored);
        fail(where, ": cannot write dataset: ", e.what());
    } catch (...) {
        std::error_code ignored;
        fs::remove_all(tmp, ignored);
        throw;
    }
}

} // namespace facesketch::dataset

#include "dataset/dataset.h"

#include "core/error.h"
#include "io/mesh_io.h"

#include <random>
#include <unistd.h>

namespace facesketch::dataset {

namespace fs = std::filesystem;

namespace {

void checkFilesExist(const fs::path& folder, const Manifest& m, const std::string& where)
{
    for (size_t i = 0; i < m.samples.size(); ++i)
        if (!fs::is_regular_file(folder / m.samples[i].file))
            fail(where, ": samples[", i, "].file: '", m.samples[i].file.string(), "' does not exist");
    for (size_t i = 0; i < m.poses.size(); ++i)
        if (!fs::is_regular_file(folder / m.poses[i].file))
            fail(where, ": poses[", i, "].file: '", m.poses[i].file.string(), "' does not exist");
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
    for (size_t i = 0; i < samples.size(); ++i) {
        const Mesh mesh = loadMesh(dataset, samples[i]->file);
        shapes.row(static_cast<Eigen::Index>(i)) = flatten(mesh.V.middleRows(begin, end - begin));
    }
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
        fill(tmp);
        writeManifest(tmp / "manifest.json", manifest);
        checkFilesExist(tmp, manifest, (folder / "manifest.json").string());
        // rename() cannot replace a non-empty folder, so the old one steps aside first and is
        // deleted only after the new one is in place.
        const bool replacing = fs::exists(folder);
        if (replacing)
            fs::rename(folder, old);
        try {
            fs::rename(tmp, folder);
        } catch (...) {
            if (replacing)
                fs::rename(old, folder);
            throw;
        }
        if (replacing)
            fs::remove_all(old);
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

#include "registration/import_scans.h"

#include "core/error.h"
#include "core/parallel.h"
#include "dataset/import_meshes.h"
#include "io/mesh_io.h"

#include <algorithm>
#include <atomic>
#include <cctype>

namespace facesketch::registration {

namespace fs = std::filesystem;

Mesh meanFace(const dataset::Dataset& dataset)
{
    if (dataset.manifest.samplesWithRole(dataset::Role::Train).empty())
        fail(dataset.folder.string(), ": the template dataset has no training faces to average");
    Mesh mesh;
    mesh.V = dataset::unflatten(dataset::loadShapes(dataset, dataset::Role::Train).colwise().mean());
    mesh.F = dataset.manifest.topology;
    return mesh;
}

ScanImport importScans(const fs::path& folder, const dataset::Dataset& templ, const fs::path& output, const ScanImportOptions& options)
{
    const double scanScale = dataset::millimetresPer(options.units, "scan units");
    const double templateScale = dataset::millimetresPer(templ.manifest.units, (templ.folder / "manifest.json").string());
    if (!fs::is_directory(folder))
        fail(folder.string(), ": not a folder");
    std::vector<fs::path> scans;
    for (const auto& entry : fs::directory_iterator(folder)) {
        std::string ext = entry.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
        if (entry.is_regular_file() && (ext == ".obj" || ext == ".ply"))
            scans.push_back(entry.path());
    }
    std::sort(scans.begin(), scans.end());
    if (scans.empty())
        fail(folder.string(), ": no .obj or .ply scans");

    Mesh mean = meanFace(templ);
    mean.V *= templateScale;
    const FeaturePoints templatePoints = landmarkPositions(mean, templ.manifest.landmarks);
    RegistrationOptions registration = options.registration;
    if (const dataset::Component* skin = templ.manifest.component("skin")) {
        registration.firstVertex = skin->begin;
        registration.endVertex = skin->end;
    }
    // Options are checked once here, so that the per-scan Errors caught below are the scans' own.
    checkRegistrationOptions(registration, mean.V.rows(), "import scans");

    // Scans register independently, each into its own slot, on all threads. The names are
    // checked afterwards in file order, so the samples and failures are the same for any number
    // of threads: a scan whose stem an earlier registered scan already has (anna.obj beside
    // anna.ply) is left out.
    struct Outcome {
        Vertices registered;
        std::string reason; ///< empty if it registered
        bool hasPoints = false;
    };
    std::vector<Outcome> outcomes(scans.size());
    const int total = static_cast<int>(scans.size());
    std::atomic<int> done { 0 };
    int reported = 0; // by the calling thread
    parallelFor(
        total, options.threads,
        [&](int i) {
            const fs::path& scan = scans[static_cast<size_t>(i)];
            const fs::path pointsFile = folder / (scan.stem().string() + ".points.json");
            Outcome& o = outcomes[static_cast<size_t>(i)];
            try {
                if (!fs::exists(pointsFile))
                    fail(scan.string(), ": no feature points ", pointsFile.string());
                o.hasPoints = true;
                Mesh mesh = readMesh(scan);
                mesh.V *= scanScale;
                FeaturePoints points = readFeaturePoints(pointsFile);
                for (auto& [name, p] : points)
                    p *= scanScale;
                o.registered = registerScan(mean, templatePoints, mesh, points, scan.string(), registration).registered / templateScale;
            } catch (const Error& e) {
                o.reason = e.what();
            }
            ++done;
        },
        [&](int i) {
            if (options.progress)
                options.progress(reported = done.load(), total, scans[static_cast<size_t>(i)].filename().string());
        });
    if (options.progress && reported < total) // another thread finished the last scans
        options.progress(total, total, scans.back().filename().string());

    ScanImport out;
    std::vector<std::pair<std::string, Vertices>> registered;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        const std::string stem = scans[i].stem().string();
        Outcome& o = outcomes[i];
        if (o.hasPoints && std::any_of(registered.begin(), registered.end(), [&](const auto& r) { return r.first == stem; }))
            o.reason = scans[i].string() + ": another scan has the name '" + stem + "'";
        if (o.reason.empty())
            registered.emplace_back(stem, std::move(o.registered));
        else
            out.failures.push_back({ scans[i], o.reason });
    }
    if (registered.empty()) {
        std::string reasons;
        for (const ScanFailure& f : out.failures)
            reasons += "\n  " + f.reason;
        fail(folder.string(), ": no scan registered:", reasons);
    }

    dataset::Manifest manifest = templ.manifest;
    manifest.samples.clear();
    manifest.poses.clear();
    const std::vector<dataset::Role> roles = dataset::shuffledRoles(static_cast<int>(registered.size()), options.seed);
    for (std::size_t i = 0; i < registered.size(); ++i)
        manifest.samples.push_back({ registered[i].first, fs::path("faces") / (registered[i].first + ".ply"), roles[i] });
    dataset::writeDataset(output, manifest, [&](const fs::path& tmp) {
        fs::create_directories(tmp / "faces");
        for (std::size_t i = 0; i < registered.size(); ++i)
            writeMesh(tmp / manifest.samples[i].file, Mesh { registered[i].second, manifest.topology });
    });
    out.manifest = manifest;
    return out;
}

} // namespace facesketch::registration

// `facesketch register TEMPLATE SCAN --points FPS.json -o OUT.ply [--error-map PNG]`: registers a
// scan of any topology into a dataset's topology (issue 15; thesis 3.2.6-3.2.12). The template is
// the dataset's mean training face with its landmarks; the skin is registered, the other
// components (eyes, teeth, tongue) follow the RBF approximation.
// `facesketch import scans DIR --template DATASET -o NEW`: every scan of a folder registered into
// a new dataset (registration/import_scans.h).
#include "commands.h"

#include "core/error.h"
#include "core/stopwatch.h"
#include "dataset/dataset.h"
#include "io/mesh_io.h"
#include "registration/error_map.h"
#include "registration/import_scans.h"
#include "registration/register.h"
#include "registration/surface_query.h"
#include "render/renderer.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>

namespace facesketch::app {

namespace {

namespace fs = std::filesystem;
using namespace facesketch::registration;

struct RegisterCommand {
    std::string templ, scan, points, output, errorMap, truth, units = "mm", method = "depth", readBack = "plane";
    RegistrationOptions options;
    double errorScale = 2.0;
    int imageSize = 800;
};

void runRegister(const RegisterCommand& c)
{
    const double scanScale = dataset::millimetresPer(c.units, "--units");
    const dataset::Dataset ds = dataset::openDataset(c.templ);
    const double templateScale = dataset::millimetresPer(ds.manifest.units, (fs::path(c.templ) / "manifest.json").string());
    // The template: the mean training face in the dataset's topology, in mm.
    Mesh templ = meanFace(ds);
    templ.V *= templateScale;
    // The scan and its points, in mm.
    Mesh scan = readMesh(c.scan);
    scan.V *= scanScale;
    FeaturePoints points = readFeaturePoints(c.points);
    for (auto& [name, p] : points)
        p *= scanScale;

    RegistrationOptions options = c.options;
    options.method = c.method == "projection" ? RegistrationMethod::Projection : RegistrationMethod::DepthMaps;
    options.readBack = c.readBack == "thesis" ? ReadBack::Thesis : c.readBack == "bilinear" ? ReadBack::Bilinear : ReadBack::Plane;
    if (const dataset::Component* skin = ds.manifest.component("skin")) {
        options.firstVertex = skin->begin;
        options.endVertex = skin->end;
    }
    const Stopwatch clock;
    const Registration r = registerScan(templ, landmarkPositions(templ, ds.manifest.landmarks), scan, points, c.scan, options);
    const double seconds = clock.seconds();

    // Measure before writing, so that a failure leaves nothing behind. Only the registered
    // vertices count (the skin; the rigid parts sit inside the head).
    const int first = options.firstVertex, end = options.endVertex < 0 ? static_cast<int>(templ.V.rows()) : options.endVertex;
    const SurfaceQuery surface(scan);
    std::vector<double> error = distanceToSurface(r.registered, surface);
    std::vector<double> before = distanceToSurface(r.approximation, surface);
    for (std::size_t v = 0; v < error.size(); ++v)
        if (r.source[v] != VertexSource::Scan || static_cast<int>(v) < first || static_cast<int>(v) >= end) {
            error[v] = std::numeric_limits<double>::quiet_NaN(); // measured only where the scan has surface
            before[v] = std::numeric_limits<double>::quiet_NaN();
        }
    const ErrorSummary summary = summarize(error), beforeSummary = summarize(before);
    // With a known true surface (a synthetic check), also the distance to it over the same vertices.
    std::vector<double> truthError;
    if (!c.truth.empty()) {
        Mesh truth = readMesh(c.truth);
        truth.V *= scanScale;
        truthError = distanceToSurface(r.registered, SurfaceQuery(truth));
        for (std::size_t v = 0; v < truthError.size(); ++v)
            if (std::isnan(error[v]))
                truthError[v] = std::numeric_limits<double>::quiet_NaN();
    }

    Mesh out { r.registered / templateScale, templ.F };
    writeMesh(c.output, out);
    int counts[4] = { 0, 0, 0, 0 };
    for (const VertexSource s : r.source)
        ++counts[static_cast<int>(s)];
    std::cout << std::fixed << std::setprecision(3) << "registered " << c.scan << " onto " << c.templ << " (" << templ.V.rows()
              << " vertices) in " << seconds << " s: wrote " << c.output << "\n";
    for (int s = 0; s < 4; ++s)
        std::cout << "  " << sourceName(static_cast<VertexSource>(s)) << ": " << counts[s] << " vertices\n";
    if (!r.points.estimated.empty()) {
        std::cout << "  estimated from the template:";
        for (const auto& name : r.points.estimated)
            std::cout << " " << name;
        std::cout << "\n";
    }
    for (const auto& name : r.points.unused)
        std::cout << "  unused (not on the template): " << name << "\n";
    if (r.refinementPoints > 0)
        std::cout << "  refined: " << c.options.refinePasses << " passes, " << r.refinementPoints
                  << " RBF points from the scan vertices (the approximation below is the last pass's)\n";
    std::cout << "  RBF approximation to scan: mean " << beforeSummary.mean << " mm, p95 " << beforeSummary.p95 << " mm, max "
              << beforeSummary.max << " mm (" << beforeSummary.measured << " vertices over the scan)\n";
    std::cout << "  registered to scan: mean " << summary.mean << " mm, p95 " << summary.p95 << " mm, max " << summary.max << " mm ("
              << summary.measured << " vertices)\n";
    if (!c.truth.empty()) {
        const ErrorSummary t = summarize(truthError);
        std::cout << "  registered to " << c.truth << ": mean " << t.mean << " mm, p95 " << t.p95 << " mm, max " << t.max << " mm ("
                  << t.measured << " vertices)\n";
    }

    if (!c.errorMap.empty()) {
        gpu::ScopedDevice deviceOwner;
        Image image;
        {
            Renderer renderer(*deviceOwner, c.imageSize, c.imageSize);
            Mesh shown { r.registered, templ.F };
            renderer.addMesh(shown, {}, errorColors(c.truth.empty() ? error : truthError, c.errorScale));
            image = renderer.render(frameMesh(shown, parseView("front"), c.imageSize, c.imageSize, Projection::Orthographic));
        }
        writePng(c.errorMap, image);
        std::cout << "  error map: " << c.errorMap << " (blue 0 mm to red " << c.errorScale << " mm, grey where the scan has no surface)\n";
    }
}

} // namespace

void addRegisterCommand(CLI::App& root)
{
    auto c = std::make_shared<RegisterCommand>();
    auto* cmd = root.add_subcommand("register",
        "Register a scan of any topology into a dataset's topology (thesis 3.2.6-3.2.12):\n"
        "RBF fit on feature points, then cylindrical depth maps (see engine/registration/register.h).");
    cmd->add_option("TEMPLATE", c->templ, "Dataset whose mean training face and landmarks are the template")->required();
    cmd->add_option("SCAN", c->scan, "Scan (.obj or .ply), any topology, holes allowed")->required();
    cmd->add_option("--points", c->points, "Feature points JSON {name: [x, y, z]} (landmark names of docs/dataset-format.md)")->required();
    cmd->add_option("-o,--output", c->output, "Registered mesh to write (.ply or .obj), in the template's units")->required();
    cmd->add_option("--error-map", c->errorMap, "PNG of the registered face coloured by its distance to the scan");
    cmd->add_option("--error-scale", c->errorScale, "Distance (mm) shown red in the error map")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->add_option("--size", c->imageSize, "Error map width and height in pixels")->capture_default_str()->check(CLI::Range(16, 8192));
    cmd->add_option("--truth", c->truth, "The scan's true surface, if known (synthetic checks): also measure, and map, the distance to it");
    cmd->add_option("--units", c->units, "Units of the scan and its points")
        ->capture_default_str()
        ->check(CLI::IsMember({ "mm", "cm", "m" }));
    cmd->add_option("--method", c->method, "depth (depth maps, 3.2.12) or projection (3.2.11)")
        ->capture_default_str()
        ->check(CLI::IsMember({ "depth", "projection" }));
    cmd->add_option("--map-size", c->options.mapWidth, "Depth map width and height in pixels")
        ->capture_default_str()
        ->check(CLI::Range(8, 8192));
    cmd->add_option("--read-back", c->readBack, "plane, bilinear or thesis (3.2.12.3 smoothing)")
        ->capture_default_str()
        ->check(CLI::IsMember({ "plane", "bilinear", "thesis" }));
    cmd->add_option("--smoothing", c->options.smoothing, "Thesis read-back: weight of the neighbouring pixels")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--blend", c->options.blendPixels, "Seam blend width beyond the scan's data, pixels")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->add_option("--max-displacement", c->options.maxDisplacement, "Scan depths farther (mm) from the approximation are ignored")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->add_option(
           "--smooth-displacement", c->options.smoothingSteps, "Umbrella steps smoothing the displacement from the approximation (0: off)")
        ->capture_default_str()
        ->check(CLI::Range(0, 100));
    cmd->add_option("--refine", c->options.refinePasses,
           "Passes that re-fit the RBF on the previous pass's scan vertices (--refine-spacing apart) and register again (0: one pass, as "
           "the thesis)")
        ->capture_default_str()
        ->check(CLI::Range(0, 4));
    cmd->add_option("--refine-spacing", c->options.refineSpacing, "Spacing (mm, on the template) of the refinement's RBF points")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->add_option("--grazing", c->options.grazingCosine,
           "Vertices whose surface meets the axis' ray at a cosine below this are re-placed from their neighbours and snapped (0: off)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 0.99));
    cmd->add_option(
           "--max-point-distance", c->options.limits.maxDistanceFromSurface, "Largest distance (mm) of a feature point from the scan")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->callback([c] {
        c->options.mapHeight = c->options.mapWidth;
        runRegister(*c);
    });
}

void addImportScansCommand(CLI::App& import)
{
    struct Options {
        std::string folder, templ, output;
        ScanImportOptions o;
        bool quiet = false;
    };
    auto o = std::make_shared<Options>();
    auto* sub = import.add_subcommand("scans",
        "Register every scan of DIR (.obj/.ply, any topology, each with <stem>.points.json)\n"
        "into a template dataset's topology (see engine/registration/import_scans.h).");
    sub->add_option("DIR", o->folder, "Folder of scans with their feature points")->required();
    sub->add_option("--template", o->templ, "Dataset whose mean training face, topology and labels are the template")->required();
    sub->add_option("-o,--output", o->output, "Dataset folder to write (replaced atomically if it is a dataset)")->required();
    sub->add_option("--units", o->o.units, "Units of the scans and their points")
        ->capture_default_str()
        ->check(CLI::IsMember({ "mm", "cm", "m" }));
    sub->add_option("--seed", o->o.seed, "Seed of the shuffle that assigns train/contour/test roles")->capture_default_str();
    sub->add_option("--map-size", o->o.registration.mapWidth, "Depth map width and height in pixels")
        ->capture_default_str()
        ->check(CLI::Range(8, 8192));
    sub->add_option("--blend", o->o.registration.blendPixels, "Seam blend width beyond the scans' data, pixels")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    sub->add_option("--smooth-displacement", o->o.registration.smoothingSteps,
           "Umbrella steps smoothing the displacement from the approximation (0: off)")
        ->capture_default_str()
        ->check(CLI::Range(0, 100));
    sub->add_option("--refine", o->o.registration.refinePasses,
           "Passes that re-fit the RBF on the previous pass's scan vertices (--refine-spacing apart) and register again (0: one pass, as "
           "the thesis)")
        ->capture_default_str()
        ->check(CLI::Range(0, 4));
    sub->add_option("--refine-spacing", o->o.registration.refineSpacing, "Spacing (mm, on the template) of the refinement's RBF points")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    sub->add_option("--grazing", o->o.registration.grazingCosine,
           "Vertices whose surface meets the axis' ray at a cosine below this are re-placed from their neighbours and snapped (0: off)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 0.99));
    sub->add_option("--threads", o->o.threads, "Scans registered at once (0: one per hardware thread)")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    sub->add_flag("-q,--quiet", o->quiet, "No progress bar");
    sub->callback([o] {
        o->o.registration.mapHeight = o->o.registration.mapWidth;
        if (!o->quiet)
            o->o.progress = [](int done, int total, const std::string& name) {
                constexpr int width = 30;
                const int filled = done * width / total;
                std::cerr << "\r[" << std::string(static_cast<size_t>(filled), '#') << std::string(static_cast<size_t>(width - filled), ' ')
                          << "] " << done << "/" << total << " " << std::left << std::setw(24) << name << std::right << std::flush;
                if (done == total)
                    std::cerr << "\n";
            };
        const Stopwatch clock;
        const ScanImport result = importScans(o->folder, dataset::openDataset(o->templ), o->output, o->o);
        for (const ScanFailure& f : result.failures)
            std::cerr << "skipped " << f.reason << "\n";
        std::cout << "wrote " << o->output << ": " << result.manifest.samples.size() << " registered scans, " << result.failures.size()
                  << " skipped, " << result.manifest.vertexCount << " vertices (" << clock.seconds() << " s)\n";
    });
}

} // namespace facesketch::app

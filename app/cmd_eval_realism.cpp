// `facesketch eval realism DATASET --reference REF [--json OUT]`: how far DATASET's faces are from
// REF's (issue 16; evaluation/realism.h): the aligned mean faces' nearest-surface distance over the
// central face region, per region, their bending (mean curvature), and the PCA modes for 90/95/99%
// of each set's variance.
#include "commands.h"

#include "core/atomic_file.h"
#include "evaluation/realism.h"

#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

namespace facesketch::app {

namespace {

struct EvalRealismCommand {
    std::string dataset, reference, json;
    double radius = evaluation::RealismOptions {}.regionRadius;
};

nlohmann::json spectrumJson(const evaluation::Spectrum& s)
{
    return { { "samples", s.samples }, { "dimensions", s.dimensions }, { "total_variance", s.totalVariance }, { "modes_90", s.modes90 },
        { "modes_95", s.modes95 }, { "modes_99", s.modes99 }, { "variances", s.variances } };
}

nlohmann::json asymmetryJson(const evaluation::Asymmetry& a)
{
    return { { "measured", a.measured }, { "share", a.share }, { "paired_vertices", a.pairedVertices }, { "message", a.message } };
}

nlohmann::json proportionsJson(const evaluation::Proportions& p)
{
    return { { "measured", p.measured }, { "message", p.message }, { "ex_ex_mm", p.biocular }, { "eyes_sn_mm", p.eyesToSn },
        { "eyes_ch_mm", p.eyesToMouth } };
}

void printAsymmetry(const char* label, const evaluation::Asymmetry& a)
{
    std::cout << std::left << std::setw(20) << label << std::right;
    if (a.measured)
        std::cout << std::setw(8) << std::setprecision(4) << a.share << "  (" << a.pairedVertices << " paired vertices)\n"
                  << std::setprecision(2);
    else
        std::cout << "  not measured: " << a.message << "\n";
}

void printSpectrum(const char* label, const evaluation::Spectrum& s)
{
    std::cout << std::left << std::setw(20) << label << std::right << std::setw(8) << s.modes90 << std::setw(8) << s.modes95 << std::setw(8)
              << s.modes99 << std::setw(10) << s.samples << std::setw(12) << s.dimensions << "\n";
}

void runEvalRealism(const EvalRealismCommand& c)
{
    const evaluation::FaceSet data = evaluation::loadFaceSet(dataset::openDataset(c.dataset));
    const evaluation::FaceSet reference = evaluation::loadFaceSet(dataset::openDataset(c.reference));
    evaluation::RealismOptions o;
    o.regionRadius = c.radius;
    const evaluation::RealismReport r = evaluation::evaluateRealism(data, reference, o);

    std::cout << std::fixed << std::setprecision(2);
    std::cout << "# " << c.dataset << " (" << data.shapes.rows() << " faces, " << data.shapes.cols() / 3 << " skin vertices) against "
              << c.reference << " (" << reference.shapes.rows() << " faces, " << reference.shapes.cols() / 3 << " skin vertices)\n";
    std::cout << "# mean faces aligned on " << r.landmarks.size() << " shared landmarks: scale " << std::setprecision(4) << r.alignmentScale
              << std::setprecision(2) << ", landmark RMS " << r.landmarkRms << " mm\n";
    std::cout << "# central region (within " << c.radius << " mm of the landmarks): " << r.dataArea << " mm^2 of the data ("
              << r.dataUncovered << " beside the reference skin), " << r.referenceArea << " mm^2 of the reference (" << r.referenceUncovered
              << " beside the data skin)\n";
    std::cout << "mean face to reference mean face, nearest-surface distance (both directions, area-weighted)\n";
    std::cout << std::left << std::setw(10) << "region" << std::right << std::setw(12) << "area mm^2" << std::setw(10) << "RMS mm"
              << std::setw(10) << "p95 mm" << std::setw(10) << "max mm"
              << "\n";
    auto row = [](const evaluation::SurfaceDistance& d) {
        std::cout << std::left << std::setw(10) << d.region << std::right << std::setw(12) << d.area << std::setw(10) << d.rms
                  << std::setw(10) << d.p95 << std::setw(10) << d.max << "\n";
    };
    for (const evaluation::SurfaceDistance& d : r.distances)
        row(d);
    std::cout << "# enclosed (the normal meets the same skin within " << o.enclosedReach
              << " mm: nostrils' insides, inner lips): " << r.dataEnclosed << " mm^2 of the data, " << r.referenceEnclosed
              << " mm^2 of the reference; `open` leaves them out\n";
    row(r.open);
    std::cout << "bending: mean curvature H (1/m, convex positive), area-weighted RMS over each mean face, RMS of the difference at\n"
                 "nearest points (both directions), and the face-to-face SD of each face's own H\n";
    std::cout << std::left << std::setw(10) << "region" << std::right << std::setw(12) << "data H" << std::setw(12) << "ref H"
              << std::setw(12) << "difference" << std::setw(14) << "data spread" << std::setw(14) << "ref spread"
              << "\n";
    for (const evaluation::Bending& b : r.bending)
        std::cout << std::left << std::setw(10) << b.region << std::right << std::setw(12) << b.dataRms << std::setw(12) << b.referenceRms
                  << std::setw(12) << b.differenceRms << std::setw(14) << b.dataSpread << std::setw(14) << b.referenceSpread << "\n";
    std::cout << "PCA modes for 90 / 95 / 99% of the variance\n";
    std::cout << std::left << std::setw(20) << "set" << std::right << std::setw(8) << "90%" << std::setw(8) << "95%" << std::setw(8)
              << "99%" << std::setw(10) << "samples" << std::setw(12) << "dimensions"
              << "\n";
    printSpectrum("data central", r.dataCentral);
    printSpectrum("reference central", r.referenceCentral);
    printSpectrum("data skin", r.dataSkin);
    printSpectrum("reference skin", r.referenceSkin);
    std::cout << "antisymmetric share of the variation, central region\n";
    printAsymmetry("data", r.dataAsymmetry);
    printAsymmetry("reference", r.referenceAsymmetry);
    std::cout << "placement: SD over faces of the shared landmarks' centroid, x / y / z mm\n";
    for (const auto& [name, sd] : { std::pair { "data", r.dataPlacement }, std::pair { "reference", r.referencePlacement } })
        std::cout << std::left << std::setw(20) << name << std::right << std::setw(8) << sd.x() << std::setw(8) << sd.y() << std::setw(8)
                  << sd.z() << "\n";
    std::cout << "proportions of each mean face: heights along up from the eye corners' mean, mm and over ex-ex\n";
    std::cout << std::left << std::setw(20) << "set" << std::right << std::setw(10) << "ex-ex" << std::setw(10) << "eyes-sn" << std::setw(8)
              << "/ex-ex" << std::setw(10) << "eyes-ch" << std::setw(8) << "/ex-ex"
              << "\n";
    for (const auto& [name, p] : { std::pair { "data", &r.dataProportions }, std::pair { "reference", &r.referenceProportions } }) {
        std::cout << std::left << std::setw(20) << name << std::right;
        if (!p->measured)
            std::cout << "  not measured: " << p->message << "\n";
        else
            std::cout << std::setw(10) << p->biocular << std::setw(10) << p->eyesToSn << std::setw(8) << p->eyesToSn / p->biocular
                      << std::setw(10) << p->eyesToMouth << std::setw(8) << p->eyesToMouth / p->biocular << "\n";
    }

    if (!c.json.empty()) {
        nlohmann::json distances = nlohmann::json::array();
        for (const evaluation::SurfaceDistance& d : r.distances)
            distances.push_back(
                { { "region", d.region }, { "area_mm2", d.area }, { "rms_mm", d.rms }, { "p95_mm", d.p95 }, { "max_mm", d.max } });
        nlohmann::json bending = nlohmann::json::array();
        for (const evaluation::Bending& b : r.bending)
            bending.push_back({ { "region", b.region }, { "data_rms_per_m", b.dataRms }, { "reference_rms_per_m", b.referenceRms },
                { "difference_rms_per_m", b.differenceRms }, { "data_spread_per_m", b.dataSpread },
                { "reference_spread_per_m", b.referenceSpread } });
        const nlohmann::json doc { { "dataset", c.dataset }, { "reference", c.reference }, { "region_radius_mm", c.radius },
            { "landmarks", r.landmarks }, { "alignment_scale", r.alignmentScale }, { "landmark_rms_mm", r.landmarkRms },
            { "data_area_mm2", r.dataArea }, { "data_uncovered_mm2", r.dataUncovered }, { "reference_area_mm2", r.referenceArea },
            { "reference_uncovered_mm2", r.referenceUncovered }, { "distances", distances }, { "bending", bending },
            { "enclosed",
                { { "reach_mm", o.enclosedReach }, { "data_mm2", r.dataEnclosed }, { "reference_mm2", r.referenceEnclosed },
                    { "open",
                        { { "area_mm2", r.open.area }, { "rms_mm", r.open.rms }, { "p95_mm", r.open.p95 }, { "max_mm", r.open.max } } } } },
            { "spectrum",
                { { "data_central", spectrumJson(r.dataCentral) }, { "reference_central", spectrumJson(r.referenceCentral) },
                    { "data_skin", spectrumJson(r.dataSkin) }, { "reference_skin", spectrumJson(r.referenceSkin) } } },
            { "asymmetry", { { "data", asymmetryJson(r.dataAsymmetry) }, { "reference", asymmetryJson(r.referenceAsymmetry) } } },
            { "proportions", { { "data", proportionsJson(r.dataProportions) }, { "reference", proportionsJson(r.referenceProportions) } } },
            { "placement_sd_mm",
                { { "data", { r.dataPlacement.x(), r.dataPlacement.y(), r.dataPlacement.z() } },
                    { "reference", { r.referencePlacement.x(), r.referencePlacement.y(), r.referencePlacement.z() } } } } };
        writeFileAtomically(c.json, [&](std::ostream& out) { out << doc.dump(1) << "\n"; });
        std::cout << "wrote " << c.json << "\n";
    }
}

} // namespace

void addEvalRealismCommand(CLI::App& eval)
{
    auto c = std::make_shared<EvalRealismCommand>();
    auto* cmd = eval.add_subcommand("realism", "How far a dataset's faces are from a reference set's: mean face and PCA spectrum");
    cmd->footer("Aligns DATASET's mean face onto REF's by a similarity on their shared landmarks and prints the nearest-surface\n"
                "distance between the two mean faces over the central face region (both directions, area-weighted RMS, 95th\n"
                "percentile, max; also per region: eyes, brows, nose, mouth, chin), how much the two mean faces bend there and\n"
                "how their bending differs (mean curvature) and varies from face to face, and for each set the number of PCA modes\n"
                "holding 90, 95 and 99% of the shape variance (central region area-weighted, and the whole skin) and the\n"
                "antisymmetric share of that variance over the central region, how far each set's faces move in their frame\n"
                "(the SD of their landmarks' centroid), and where each mean face has its eyes between sn and the mouth's corners. Every "
                "sample of both datasets is used. --json writes the "
                "same figures and each spectrum (docs/realism.md).");
    cmd->add_option("dataset", c->dataset, "Dataset folder to measure (e.g. facesketch synth)")->required();
    cmd->add_option("--reference", c->reference, "Reference dataset folder (e.g. an ICT import)")->required();
    cmd->add_option("--radius", c->radius, "Central region: within this many mm of the shared landmarks")
        ->capture_default_str()
        ->check(CLI::Range(1e-3, 1000.0));
    cmd->add_option("--json", c->json, "Write the figures to this JSON file");
    cmd->callback([c] { runEvalRealism(*c); });
}

} // namespace facesketch::app

#include "bench.h"
#include "commands.h"

#include "core/error.h"

#include <algorithm>
#include <iostream>

namespace facesketch::app {

const std::vector<Benchmark>& benchmarks()
{
    static const std::vector<Benchmark> all = {
        {"normals", "area-weighted vertex normals of a batch of meshes: GPU kernel vs single-threaded CPU", benchNormals},
        {"render", "offscreen render of a lit mesh to an image, with readback", benchRender},
        {"contours", "curvature pass and per-view candidate cloud of 230 synthetic faces (--vertices picks low, high or ultra): GPU vs single-threaded CPU", benchContours},
        {"synth", "250 synthetic identities at each resolution, 250 ICT identities, 10 identities with their 36 poses", benchSynth},
        {"stats", "statistics core at 6,000 vertices: conditional inference, reconstruction, one mixture fit", benchStatsCore},
        {"train", "face model on the synthetic low, high and ultra sets: training time, file size, reconstruction latency", benchTrain},
    };
    return all;
}

double median(std::vector<double>& samples)
{
    if (samples.empty())
        return 0;
    std::nth_element(samples.begin(), samples.begin() + samples.size() / 2, samples.end());
    return samples[samples.size() / 2];
}

void addBenchCommand(CLI::App& root)
{
    auto* cmd = root.add_subcommand("bench", "Run a benchmark; prints `name value unit` lines");
    auto name = std::make_shared<std::string>();
    auto options = std::make_shared<BenchOptions>();
    auto list = std::make_shared<bool>(false);
    cmd->add_option("name", *name, "Benchmark to run (see --list), or `all`");
    cmd->add_flag("--list", *list, "List the benchmarks");
    cmd->add_option("--repeat", options->repeat, "Timed repetitions (median reported)")->check(CLI::Range(1, 10000));
    cmd->add_option("--meshes", options->meshes, "Meshes per batch")->check(CLI::Range(1, 100000));
    cmd->add_option("--vertices", options->vertices, "Vertices per mesh")->check(CLI::Range(4, 10000000));
    cmd->add_option("--pass1", options->pass1, "contours: SPIR-V of a pass-1 variant, timed against the built-in kernel");
    cmd->add_option("--pass2", options->pass2, "contours: SPIR-V of a pass-2 variant, timed against the built-in kernel");
    cmd->callback([=] {
        if (*list || name->empty()) {
            for (const Benchmark& b : benchmarks())
                std::cout << b.name << "\t" << b.description << "\n";
            return;
        }
        bool ran = false;
        for (const Benchmark& b : benchmarks())
            if (*name == "all" || *name == b.name) {
                b.run(*options, std::cout);
                ran = true;
            }
        if (!ran)
            fail("no benchmark named '", *name, "' (facesketch bench --list shows them)");
    });
}

} // namespace facesketch::app

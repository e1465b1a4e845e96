#include "bench.h"
#include "commands.h"

#include "core/error.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <iostream>
#include <sstream>

namespace facesketch::app {

namespace {

// The machine's CPU time from /proc/stat: total and stolen by the hypervisor (jiffies), or
// zeros where there is no /proc/stat. On a shared virtual machine steal is what makes figures
// swing by 2x between runs, so each benchmark reports how much of its time was stolen.
std::array<unsigned long long, 2> cpuTimes()
{
    std::ifstream in("/proc/stat");
    std::string line, label;
    if (!std::getline(in, line))
        return { 0, 0 };
    std::istringstream fields(line);
    fields >> label;
    unsigned long long total = 0, value = 0, steal = 0;
    for (int i = 0; fields >> value; ++i) {
        if (i < 8) // user nice system idle iowait irq softirq steal; guest time is inside user
            total += value;
        if (i == 7)
            steal = value;
    }
    return { total, steal };
}

} // namespace

const std::vector<Benchmark>& benchmarks()
{
    static const std::vector<Benchmark> all = {
        { "normals", "area-weighted vertex normals of a batch of meshes: GPU kernel vs single-threaded CPU", benchNormals },
        { "render", "offscreen render of a lit mesh to an image, with readback", benchRender },
        { "contours",
            "curvature pass and per-view candidate cloud of 230 synthetic faces (--vertices picks low, high or ultra): GPU vs "
            "single-threaded CPU",
            benchContours },
        { "synth", "250 synthetic identities at each resolution, 250 ICT identities, 10 identities with their 36 poses", benchSynth },
        { "stats", "statistics core at 6,000 vertices: conditional inference, reconstruction, one mixture fit", benchStatsCore },
        { "train", "face model on the synthetic low, high and ultra sets: training time, file size, reconstruction latency", benchTrain },
        { "sketch",
            "one ~60-point stroke from the session file to the updated face on the synthetic low, high and ultra sets, with its parts",
            benchSketch },
        { "register", "registering one 100,000-triangle scan onto a 6,000-vertex template: depth maps and projection", benchRegister },
        { "pose", "one timeline frame (cardinal spline + FP-to-mesh mapping rebuild) at about 900, 6,000 and 25,000 vertices", benchPose },
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
                const auto before = cpuTimes();
                b.run(*options, std::cout);
                const auto after = cpuTimes();
                if (after[0] > before[0])
                    std::cout << "# " << b.name << ": " << 100.0 * double(after[1] - before[1]) / double(after[0] - before[0])
                              << "% of the machine's CPU time was stolen by the hypervisor (figures swing with it)\n";
                ran = true;
            }
        if (!ran)
            fail("no benchmark named '", *name, "' (facesketch bench --list shows them)");
    });
}

} // namespace facesketch::app

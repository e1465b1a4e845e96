// Benchmarks of dataset generation: 250 synthetic identities at each resolution and 250
// identities imported from the ICT Face Model (issue 3's goal: under 30 s each on 2 cores).

#include "bench.h"

#include "core/stopwatch.h"
#include "dataset/import_ict.h"
#include "dataset/synth/synth_dataset.h"

#include <cstdlib>
#include <filesystem>
#include <random>
#include <thread>

namespace facesketch::app {

void benchSynth(const BenchOptions&, std::ostream& out)
{
    namespace fs = std::filesystem;
    const fs::path root = fs::temp_directory_path() / ("facesketch-bench-synth-" + std::to_string(std::random_device {}()));
    fs::create_directories(root);
    out << "# 250 identities, neutral faces only, " << std::thread::hardware_concurrency() << " threads, written to " << root.string()
        << "\n";
    try {
        for (auto resolution : { dataset::Resolution::Low, dataset::Resolution::High, dataset::Resolution::Ultra }) {
            dataset::SynthOptions o;
            o.resolution = resolution;
            Stopwatch clock;
            dataset::writeSynthDataset(root / dataset::resolutionName(resolution), o);
            out << "synth_250_" << dataset::resolutionName(resolution) << "_s " << clock.seconds() << " s\n";
            fs::remove_all(root / dataset::resolutionName(resolution));
        }
        // The ICT model beside the source tree, as the tests find it, or FACESKETCH_ICT_DIR.
        const char* env = std::getenv("FACESKETCH_ICT_DIR");
        const fs::path ict = env && *env ? fs::path(env) : fs::path(FACESKETCH_SOURCE_DIR) / ".." / "shared" / "datasets" / "ict-facekit";
        if (fs::is_directory(ict)) {
            dataset::IctOptions o;
            o.identities = 250;
            Stopwatch clock;
            dataset::writeIctDataset(ict, root / "ict", o);
            out << "import_ict_250_s " << clock.seconds() << " s\n";
            fs::remove_all(root / "ict");
        } else {
            out << "# no ICT Face Model at " << ict.string() << " (set FACESKETCH_ICT_DIR): import_ict_250_s not measured\n";
        }
        dataset::SynthOptions posed;
        posed.identities = 10;
        posed.poses = true;
        Stopwatch clock;
        dataset::writeSynthDataset(root / "poses", posed);
        out << "synth_10x36_poses_low_s " << clock.seconds() << " s\n";
    } catch (...) {
        fs::remove_all(root);
        throw;
    }
    fs::remove_all(root);
}

} // namespace facesketch::app

#pragma once
// `facesketch bench NAME`: each benchmark prints one figure per line as `name value unit`
// (e.g. `normals_gpu_ms 3.2 ms`) on stdout, and context (device, sizes) as `# ...` lines, so
// figures can be collected by script. BENCHMARKS.md records them with the command.

#include <ostream>
#include <string>
#include <vector>

namespace facesketch::app {

struct BenchOptions {
    int repeat = 10;     ///< timed repetitions; the median is reported
    int meshes = 230;    ///< batch size for dataset kernels (the thesis' 230 cached faces)
    int vertices = 6000; ///< vertices per mesh
    /// contours: SPIR-V files of pass 1 and pass 2 variants (ContourKernels), each timed against
    /// the built-in kernel in the same process; empty: none.
    std::string pass1, pass2;
};

struct Benchmark {
    std::string name;
    std::string description;
    void (*run)(const BenchOptions&, std::ostream&);
};

const std::vector<Benchmark>& benchmarks();

void benchNormals(const BenchOptions& options, std::ostream& out);
void benchRender(const BenchOptions& options, std::ostream& out);
void benchContours(const BenchOptions& options, std::ostream& out);
void benchStatsCore(const BenchOptions& options, std::ostream& out);
void benchTrain(const BenchOptions& options, std::ostream& out);
void benchSynth(const BenchOptions& options, std::ostream& out);
void benchSketch(const BenchOptions& options, std::ostream& out);
void benchRegister(const BenchOptions& options, std::ostream& out);
void benchPose(const BenchOptions& options, std::ostream& out);

/// Median of `samples` (which it reorders).
double median(std::vector<double>& samples);

} // namespace facesketch::app

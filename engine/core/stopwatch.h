#pragma once
// Wall-clock timing for benchmarks and progress reports.

#include <chrono>

namespace facesketch {

class Stopwatch {
public:
    Stopwatch()
        : start_(std::chrono::steady_clock::now())
    {
    }
    void restart() { start_ = std::chrono::steady_clock::now(); }
    double milliseconds() const { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count(); }
    double seconds() const { return milliseconds() * 1e-3; }

private:
    std::chrono::steady_clock::time_point start_;
};

} // namespace facesketch

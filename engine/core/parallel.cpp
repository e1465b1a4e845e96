#include "core/parallel.h"

#include "core/error.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace facesketch {

void parallelFor(int count, int threads, const std::function<void(int)>& body, const std::function<void(int)>& onCaller)
{
    if (count < 0)
        fail("parallelFor: count ", count, " is negative");
    if (threads < 0)
        fail("parallelFor: threads ", threads, " is negative (0 means one per hardware thread)");
    if (count == 0)
        return;
    if (threads == 0)
        threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::min(threads, count);

    std::atomic<int> next { 0 };
    std::exception_ptr error; // of the lowest failing index so far
    int errorIndex = count;
    std::mutex errorMutex;
    auto work = [&](bool caller) {
        for (int i = next++; i < count; i = next++) {
            try {
                body(i);
                if (caller && onCaller)
                    onCaller(i);
            } catch (...) {
                std::lock_guard<std::mutex> lock(errorMutex);
                if (i < errorIndex) {
                    error = std::current_exception();
                    errorIndex = i;
                }
                next = count; // stop handing out indices
            }
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(static_cast<size_t>(threads - 1));
    try {
        for (int t = 1; t < threads; ++t)
            pool.emplace_back(work, false);
    } catch (...) { // no more threads to be had: the ones started and this one do the work
    }
    work(true);
    for (std::thread& t : pool)
        t.join();
    if (error)
        std::rethrow_exception(error);
}

} // namespace facesketch

// Jobs on a worker thread: progress, completion, cancellation and failure.
#include "gui/worker.h"

#include "core/error.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <thread>

using namespace facesketch;
using namespace facesketch::gui;

TEST_CASE("worker: a job runs off the calling thread and reports progress until done")
{
    std::atomic<bool> go { false };
    std::thread::id worker;
    int result = 0;
    Job job("count", [&](Progress& p) {
        worker = std::this_thread::get_id();
        p.report(0.25, "waiting");
        while (!go)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        for (int i = 1; i <= 10; ++i) {
            result += i;
            p.report(0.25 + 0.075 * i, "adding");
        }
    });
    // The job waits for `go`, so the caller sees it running with its first report.
    while (job.stage().empty())
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    REQUIRE(job.state() == Job::State::Running);
    REQUIRE(job.fraction() == Approx(0.25));
    REQUIRE(job.stage() == "waiting");
    go = true;
    job.wait();
    REQUIRE(job.state() == Job::State::Done);
    REQUIRE(job.fraction() == 1.0);
    REQUIRE(result == 55);
    REQUIRE(worker != std::this_thread::get_id());
    REQUIRE(job.error().empty());
}

TEST_CASE("worker: cancel stops the work at its next report")
{
    std::atomic<int> steps { 0 };
    Job job("endless", [&](Progress& p) {
        for (;;) {
            ++steps;
            p.report(0.5, "spinning");
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    });
    while (steps < 3)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    job.cancel();
    job.wait();
    REQUIRE(job.state() == Job::State::Cancelled);
    const int after = steps;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    REQUIRE(steps == after);
    REQUIRE_NOTHROW(job.rethrow());
}

TEST_CASE("worker: an error in the work fails the job with its message")
{
    Job job("broken", [](Progress& p) {
        p.report(0.1, "reading");
        fail("faces.model: truncated at byte 12");
    });
    job.wait();
    REQUIRE(job.state() == Job::State::Failed);
    REQUIRE(job.error() == "faces.model: truncated at byte 12");
    REQUIRE_THROWS_AS(job.rethrow(), Error);
}

TEST_CASE("worker: destroying a running job cancels it and waits")
{
    std::atomic<bool> ended { false };
    {
        Job job("long", [&](Progress& p) {
            try {
                for (;;) {
                    p.checkCancelled();
                    std::this_thread::sleep_for(std::chrono::milliseconds(1));
                }
            } catch (const Cancelled&) {
                ended = true;
                throw;
            }
        });
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    REQUIRE(ended);
}

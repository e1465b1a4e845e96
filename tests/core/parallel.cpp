// Tests of core/parallel: every index runs once whatever the threads, one thread keeps the
// order on the calling thread, onCaller runs only there, and an error stops the work and
// reaches the caller after every thread has joined, the lowest failing index's when several fail.
#include "core/parallel.h"
#include "core/error.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace facesketch;

TEST_CASE("parallelFor: every index runs exactly once, for any number of threads")
{
    for (const int threads : { 0, 1, 2, 3, 8 }) {
        for (const int count : { 0, 1, 2, 7, 1000 }) {
            std::vector<std::atomic<int>> runs(static_cast<size_t>(count));
            parallelFor(count, threads, [&](int i) { ++runs[static_cast<size_t>(i)]; });
            for (int i = 0; i < count; ++i)
                REQUIRE(runs[static_cast<size_t>(i)].load() == 1);
        }
    }
}

TEST_CASE("parallelFor: one thread runs the indices in order on the calling thread")
{
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<int> order, reported;
    parallelFor(
        20, 1,
        [&](int i) {
            REQUIRE(std::this_thread::get_id() == caller);
            order.push_back(i);
        },
        [&](int i) { reported.push_back(i); });
    REQUIRE(order.size() == 20);
    for (int i = 0; i < 20; ++i)
        REQUIRE(order[static_cast<size_t>(i)] == i);
    REQUIRE(reported == order);
}

TEST_CASE("parallelFor: onCaller runs on the calling thread only, after each index that thread ran")
{
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<int> ranOnCaller, reported; // touched by the calling thread only
    std::atomic<int> wrongThread { 0 };
    // The other threads wait until the calling thread has run an index, so it runs some
    // whatever the scheduling (with 200 quick indices the others could otherwise take them all).
    // It always gets one: the other three threads hold one index each at most while waiting.
    std::atomic<bool> callerRan { false };
    parallelFor(
        200, 4,
        [&](int i) {
            if (std::this_thread::get_id() == caller) {
                ranOnCaller.push_back(i);
                callerRan = true;
            } else
                while (!callerRan)
                    std::this_thread::yield();
        },
        [&](int i) {
            if (std::this_thread::get_id() != caller)
                ++wrongThread;
            else
                reported.push_back(i);
        });
    REQUIRE(wrongThread.load() == 0);
    REQUIRE(!reported.empty());
    REQUIRE(reported == ranOnCaller);
}

TEST_CASE("parallelFor: an error stops the work and is rethrown after the join, the lowest failing index's")
{
    // One thread: nothing after the failing index runs.
    std::vector<int> ran;
    REQUIRE_THROWS_WITH(parallelFor(10, 1,
                            [&](int i) {
                                ran.push_back(i);
                                if (i == 3)
                                    throw std::runtime_error("index 3 failed");
                            }),
        "index 3 failed");
    REQUIRE(ran == std::vector<int> { 0, 1, 2, 3 });

    // Several threads: the error reaches the caller, and not every index started (each other
    // index takes 1 ms, so all 1,000 would take a third of a second on three threads).
    std::atomic<int> started { 0 };
    REQUIRE_THROWS_WITH(parallelFor(1000, 4,
                            [&](int i) {
                                ++started;
                                if (i == 0)
                                    throw std::runtime_error("first index failed");
                                std::this_thread::sleep_for(std::chrono::milliseconds(1));
                            }),
        "first index failed");
    REQUIRE(started.load() < 1000);

    // Two failing indices: the lower one's error is rethrown, even when the higher one fails
    // first (index 3 waits until index 7 has thrown).
    for (const int threads : { 1, 2, 4 }) {
        std::atomic<bool> sevenThrew { false };
        REQUIRE_THROWS_WITH(parallelFor(10, threads,
                                [&](int i) {
                                    if (i == 7) {
                                        sevenThrew = true;
                                        throw std::runtime_error("index 7 failed");
                                    }
                                    if (i == 3) {
                                        for (int wait = 0; threads > 1 && !sevenThrew && wait < 2000; ++wait)
                                            std::this_thread::sleep_for(std::chrono::milliseconds(1));
                                        throw std::runtime_error("index 3 failed");
                                    }
                                }),
            "index 3 failed");
    }

    // An error in onCaller stops the work too.
    int calls = 0;
    REQUIRE_THROWS_WITH(parallelFor(
                            5, 1, [&](int) { ++calls; }, [](int) { throw std::runtime_error("report failed"); }),
        "report failed");
    REQUIRE(calls == 1);
}

TEST_CASE("parallelFor: a negative count or number of threads is an error naming the value")
{
    REQUIRE_THROWS_AS(parallelFor(-1, 1, [](int) {}), Error);
    REQUIRE_THROWS_WITH(parallelFor(-1, 1, [](int) {}), Catch::Contains("count -1"));
    REQUIRE_THROWS_WITH(parallelFor(3, -2, [](int) {}), Catch::Contains("threads -2"));
}

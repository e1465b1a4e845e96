#pragma once
// Long work off the window's thread (loading a dataset, the curvature pass, synthesising and
// training the built-in data): a Job runs a function on its own thread, which reports progress
// (a fraction and a stage) and checks for cancellation; the window polls both every frame and
// draws a progress bar with a Cancel button, so it never freezes.
//
// Cancellation is cooperative: cancel() asks, and the work stops at its next report() or
// checkCancelled() (each throws Cancelled then), so the granularity is that of the work's
// progress reports (one mesh of synthesis, one step of training).

#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

namespace facesketch::gui {

/// Thrown inside a job's work when cancel() was asked; ends the job as cancelled.
struct Cancelled : std::runtime_error {
    Cancelled()
        : std::runtime_error("cancelled")
    {
    }
};

/// What the work sees: report progress, and learn about cancellation.
class Progress {
public:
    /// Sets the fraction done (clamped to [0, 1]) and the stage's name; throws Cancelled if
    /// the job was cancelled.
    void report(double fraction, const std::string& stage);
    /// Throws Cancelled if the job was cancelled.
    void checkCancelled() const;
    bool cancelled() const { return cancel_.load(); }

private:
    friend class Job;
    std::atomic<bool> cancel_ { false };
    std::atomic<double> fraction_ { 0 };
    mutable std::mutex mutex_;
    std::string stage_;
};

class Job {
public:
    enum class State { Running, Done, Failed, Cancelled };

    /// Starts `work` on a new thread at once.
    Job(std::string name, std::function<void(Progress&)> work);
    /// Asks the work to stop and waits for the thread (a job never outlives its owner).
    ~Job();
    Job(const Job&) = delete;
    Job& operator=(const Job&) = delete;

    const std::string& name() const { return name_; }
    State state() const { return state_.load(); }
    bool finished() const { return state() != State::Running; }
    double fraction() const { return progress_.fraction_.load(); }
    std::string stage() const;
    /// Asks the work to stop at its next report.
    void cancel() { progress_.cancel_ = true; }
    /// Waits until the work has ended (any state).
    void wait();
    /// The exception's message when Failed (empty otherwise).
    std::string error() const;
    /// Rethrows the work's exception when Failed (does nothing otherwise).
    void rethrow() const;

private:
    std::string name_;
    Progress progress_;
    std::atomic<State> state_ { State::Running };
    std::exception_ptr exception_;
    std::string error_;
    std::thread thread_;
};

} // namespace facesketch::gui

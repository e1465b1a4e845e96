#include "gui/worker.h"

#include <algorithm>

namespace facesketch::gui {

void Progress::report(double fraction, const std::string& stage)
{
    fraction_ = std::clamp(fraction, 0.0, 1.0);
    {
        std::lock_guard lock(mutex_);
        stage_ = stage;
    }
    checkCancelled();
}

void Progress::checkCancelled() const
{
    if (cancel_.load())
        throw Cancelled();
}

Job::Job(std::string name, std::function<void(Progress&)> work)
    : name_(std::move(name))
{
    // exception_ and error_ are written before state_ leaves Running and read only after.
    thread_ = std::thread([this, work = std::move(work)] {
        try {
            work(progress_);
            progress_.fraction_ = 1.0;
            state_ = State::Done;
        } catch (const Cancelled&) {
            state_ = State::Cancelled;
        } catch (const std::exception& e) {
            exception_ = std::current_exception();
            error_ = e.what();
            state_ = State::Failed;
        } catch (...) {
            exception_ = std::current_exception();
            error_ = "unknown error";
            state_ = State::Failed;
        }
    });
}

Job::~Job()
{
    cancel();
    wait();
}

void Job::wait()
{
    if (thread_.joinable())
        thread_.join();
}

std::string Job::stage() const
{
    std::lock_guard lock(progress_.mutex_);
    return progress_.stage_;
}

std::string Job::error() const
{
    return finished() ? error_ : std::string();
}

void Job::rethrow() const
{
    if (state() == State::Failed && exception_)
        std::rethrow_exception(exception_);
}

} // namespace facesketch::gui

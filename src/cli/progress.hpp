// The progress line on stderr: "cbr recover: recovering... 3.4 s",
// rewritten in place (\r) a few times a second while a step runs, for steps
// that last more than about a second, and erased when the step ends. Only
// when enabled (the commands enable it when stderr is a terminal and -q is
// not given); disabled, it writes nothing and starts no thread.
//
// A background thread does the writing, since libcbr's calls do not come
// back before they are done. Whoever else writes to stderr or stdout calls
// clear() first (Steps does, see steps.hpp).
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace cbr::cli {

class ProgressLine {
public:
    ProgressLine(std::string prefix, bool enabled);
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;
    ~ProgressLine();  // clears the line and stops the thread

    // Starts step `name` (its clock restarts), erasing the previous one.
    void show(const std::string& name);
    // Erases the line; nothing is shown until the next show().
    void clear();

    // True when stderr is a terminal.
    static bool stderr_is_terminal();

private:
    void run();
    void erase_locked();
    void draw_locked(double seconds);

    const std::string prefix_;
    bool enabled_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::thread thread_;
    std::string step_;  // empty: nothing to show
    std::chrono::steady_clock::time_point since_;
    std::size_t drawn_ = 0;  // characters on the line now
    bool stop_ = false;
};

}  // namespace cbr::cli

// The steps of a command run ("reading", "inserting points", ...): each
// one drives the progress line (progress.hpp) and is timed with
// steady_clock. With the environment variable CBR_TIMING=1, report_timing()
// prints one line on stderr:
//
//   cbr recover: timing: reading 0.051 s, inserting points 0.210 s, ...;
//   total 1.702 s; reading + writing 0.400 s = 23.5% of total
//
// (one line), where "total" runs from the construction of Steps to the
// call, and reading + writing sums the steps begun with io = true.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "cli/progress.hpp"

namespace cbr::cli {

class Steps {
public:
    // `command` names the command in the lines ("recover"); the progress
    // line is shown when stderr is a terminal and not `quiet`.
    Steps(const std::string& command, bool quiet);

    // Ends the current step, if any, and starts `name`.
    void begin(const char* name, bool io = false);
    // Ends the current step and erases the progress line: call before
    // printing anything.
    void end();
    // Ends the current step; with CBR_TIMING=1, prints the timing line.
    void report_timing();

private:
    struct Step {
        const char* name;
        bool io;
        double seconds;
    };
    using Clock = std::chrono::steady_clock;

    const std::string command_;
    const Clock::time_point start_;
    ProgressLine progress_;
    std::vector<Step> done_;
    const char* current_ = nullptr;
    bool current_io_ = false;
    Clock::time_point since_;
};

}  // namespace cbr::cli

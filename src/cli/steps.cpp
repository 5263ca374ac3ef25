#include "cli/steps.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace cbr::cli {

Steps::Steps(const std::string& command, bool quiet)
    : command_(command),
      start_(Clock::now()),
      progress_("cbr " + command + ": ", !quiet && ProgressLine::stderr_is_terminal()) {}

void Steps::begin(const char* name, bool io) {
    end();
    current_ = name;
    current_io_ = io;
    since_ = Clock::now();
    progress_.show(name);
}

void Steps::end() {
    progress_.clear();
    if (current_ == nullptr) return;
    done_.push_back({current_, current_io_, std::chrono::duration<double>(Clock::now() - since_).count()});
    current_ = nullptr;
}

void Steps::report_timing() {
    end();
    const char* env = std::getenv("CBR_TIMING");
    if (env == nullptr || std::strcmp(env, "1") != 0) return;
    const double total = std::chrono::duration<double>(Clock::now() - start_).count();
    double io = 0;
    std::string line = "cbr " + command_ + ": timing:";
    char buf[64];
    for (std::size_t i = 0; i < done_.size(); ++i) {
        std::snprintf(buf, sizeof buf, " %.3f s", done_[i].seconds);
        line += (i == 0 ? " " : ", ") + std::string(done_[i].name) + buf;
        if (done_[i].io) io += done_[i].seconds;
    }
    std::snprintf(buf, sizeof buf, "; total %.3f s; reading + writing %.3f s = %.1f%% of total", total, io,
                  total > 0 ? 100 * io / total : 0.0);
    line += buf;
    std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace cbr::cli

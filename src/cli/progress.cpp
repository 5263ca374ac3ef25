#include "cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <system_error>
#include <utility>

namespace cbr::cli {
namespace {

constexpr std::chrono::milliseconds kDelay{1000};   // a step shorter than this shows nothing
constexpr std::chrono::milliseconds kRefresh{200};  // time between two redraws

}  // namespace

ProgressLine::ProgressLine(std::string prefix, bool enabled) : prefix_(std::move(prefix)), enabled_(enabled) {}

ProgressLine::~ProgressLine() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        erase_locked();
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
}

bool ProgressLine::stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

void ProgressLine::show(const std::string& name) {
    if (!enabled_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    erase_locked();
    step_ = name;
    since_ = std::chrono::steady_clock::now();
    if (thread_.joinable()) return;
    try {
        thread_ = std::thread([this] { run(); });
    } catch (const std::system_error&) {
        enabled_ = false;  // no thread, no progress line: the run goes on
        step_.clear();
    }
}

void ProgressLine::clear() {
    if (!enabled_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    erase_locked();
    step_.clear();
}

void ProgressLine::run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
        wake_.wait_for(lock, kRefresh);
        if (stop_ || step_.empty()) continue;
        const auto elapsed = std::chrono::steady_clock::now() - since_;
        if (elapsed >= kDelay) draw_locked(std::chrono::duration<double>(elapsed).count());
    }
}

void ProgressLine::erase_locked() {
    if (drawn_ == 0) return;
    std::string line = "\r";
    line.append(drawn_, ' ');
    line += '\r';
    std::fwrite(line.data(), 1, line.size(), stderr);
    std::fflush(stderr);
    drawn_ = 0;
}

void ProgressLine::draw_locked(double seconds) {
    char clock[32];
    std::snprintf(clock, sizeof clock, "... %.1f s", seconds);
    const std::string text = prefix_ + step_ + clock;
    std::string line = "\r" + text;
    if (drawn_ > text.size()) line.append(drawn_ - text.size(), ' ');
    std::fwrite(line.data(), 1, line.size(), stderr);
    std::fflush(stderr);
    drawn_ = std::max(drawn_, text.size());
}

}  // namespace cbr::cli

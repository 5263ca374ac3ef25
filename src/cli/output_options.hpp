// The options that commands writing a mesh share (-o OUT, --json FILE, -q)
// and their checks, so every such command parses them alike.
#pragma once

#include <string>

namespace cbr::cli {

struct OutputOptions {
    std::string output, json;
    bool quiet = false;
};

// Usage error of `command` ("recover", "demo"): one line on stderr, exit 1.
int usage_error(const char* command, const std::string& message);

// If argv[i] is one of the shared options, takes it (and its value,
// advancing i) and returns true; `error` is then set to an exit code when
// the option is malformed, else left alone.
bool take_output_option(const char* command, int argc, char** argv, int& i, OutputOptions& options, int& error);

// After parsing: --json and -o differ, and -o (when given) names a format
// the writers know. Returns an exit code, or -1 when all is well.
int check_output_options(const char* command, const OutputOptions& options);

}  // namespace cbr::cli

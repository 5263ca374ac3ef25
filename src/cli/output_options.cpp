#include "cli/output_options.hpp"

#include <cstdio>

#include "cli/exit_codes.hpp"
#include "io/write_volume.hpp"

namespace cbr::cli {

int usage_error(const char* command, const std::string& message) {
    std::fprintf(stderr, "cbr %s: %s (try cbr %s --help)\n", command, message.c_str(), command);
    return kExitUsage;
}

bool take_output_option(const char* command, int argc, char** argv, int& i, OutputOptions& options, int& error) {
    const std::string a = argv[i];
    if (a == "-q") {
        options.quiet = true;
        return true;
    }
    if (a != "-o" && a != "--json") return false;
    if (++i >= argc) {
        error = usage_error(command, a + " needs a file name");
        return true;
    }
    (a == "-o" ? options.output : options.json) = argv[i];
    return true;
}

int check_output_options(const char* command, const OutputOptions& options) {
    if (!options.json.empty() && options.json == options.output)
        return usage_error(command, "--json and -o name the same file");
    if (!options.output.empty() && !io::is_volume_file(options.output)) {
        std::fprintf(stderr, "cbr %s: %s: unknown output format (known: %s)\n", command, options.output.c_str(),
                     io::volume_extensions());
        return kExitIo;
    }
    return -1;
}

}  // namespace cbr::cli

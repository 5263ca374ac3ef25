#include "cli/volume_command.hpp"

#include <cbr/cbr.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>

#include "cli/exit_codes.hpp"
#include "cli/output_options.hpp"
#include "cli/recovery_run.hpp"
#include "cli/run_report.hpp"
#include "cli/steps.hpp"
#include "cli/table_one.hpp"
#include "cli/table_two.hpp"
#include "io/read_surface.hpp"

namespace cbr::cli {
namespace {

constexpr int kContinue = -1;

struct VolumeArgs : OutputOptions {
    std::string input;
    double size = 0;    // mesh --size H; 0: from the surface
    double growth = -1;  // mesh --growth R; < 0: not given (the library's default)
    bool keep_exterior = false;
    bool allow_open = false;
    bool triangulate = false;  // --triangulate: faces with more than 3 corners as triangle fans
    bool deep_flips = true;
    bool retries = true;
    int threads = 0;  // --threads N; 0: as many as the hardware runs at once
};

// The largest --threads (CBR_PARAM_THREADS' range).
constexpr int kMaxThreads = 256;

// A whole number within [0, kMaxThreads].
bool parse_threads(const char* text, int& out) {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(text, &end, 10);
    if (errno != 0 || end == text || *end != '\0' || v < 0 || v > kMaxThreads) return false;
    out = static_cast<int>(v);
    return true;
}

// A finite number > 0 (or >= 0 with allow_zero).
bool parse_length(const char* text, double& out, bool allow_zero = false) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text, &end);
    if (errno != 0 || end == text || *end != '\0' || !std::isfinite(v)) return false;
    if (!(v > 0) && !(allow_zero && v == 0)) return false;
    out = v;
    return true;
}

int parse_args(int argc, char** argv, const VolumeCommand& command, VolumeArgs& args) {
    const char* name = command.name;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help") {
            command.print_help(stdout);
            return kExitOk;
        }
        int error = kContinue;
        if (take_output_option(name, argc, argv, i, args, error)) {
            if (error != kContinue) return error;
        } else if (command.refine && a == "--size") {
            if (i + 1 >= argc) return usage_error(name, "--size needs a length");
            if (!parse_length(argv[++i], args.size))
                return usage_error(name, std::string("--size needs a finite length > 0, not '") + argv[i] + "'");
        } else if (command.refine && a == "--growth") {
            if (i + 1 >= argc) return usage_error(name, "--growth needs a rate");
            if (!parse_length(argv[++i], args.growth, true) || args.growth > 100)
                return usage_error(name, std::string("--growth needs a rate within [0, 100], not '") + argv[i] + "'");
        } else if (a == "--keep-exterior") {
            args.keep_exterior = true;
        } else if (a == "--allow-open") {
            args.allow_open = true;
        } else if (a == "--triangulate") {
            args.triangulate = true;
        } else if (a == "--no-deep-flips") {
            args.deep_flips = false;
        } else if (a == "--no-retries") {
            args.retries = false;
        } else if (a == "--threads") {
            if (i + 1 >= argc) return usage_error(name, "--threads needs a number");
            if (!parse_threads(argv[++i], args.threads))
                return usage_error(name, "--threads needs a whole number within [0, " + std::to_string(kMaxThreads) +
                                             "], not '" + argv[i] + "'");
        } else if (!a.empty() && a[0] == '-') {
            return usage_error(name, "unknown option '" + a + "'");
        } else if (!args.input.empty()) {
            return usage_error(name, "one input file only");
        } else {
            args.input = a;
        }
    }
    if (args.input.empty()) return usage_error(name, "no input file");
    if (args.output.empty()) return usage_error(name, "no output file (-o OUT)");
    return check_output_options(name, args);
}

void print_refine(std::FILE* out, const RefineSummary& r) {
    std::fprintf(out, "Mesh generation (Du & Wang 2004, section 6)\n");
    std::fprintf(out, "  %-36s%12.0f\n", "field points inserted", r.field_points);
    std::fprintf(out, "  %-36s%12.0f\n", "quality flips", r.flips);
    std::fprintf(out, "  %-36s%12.0f\n", "tetrahedra over the size bound", r.oversize_tets);
    std::fprintf(out, "  time: refinement %.3f s\n", r.seconds);
}

int run(const VolumeCommand& command, const VolumeArgs& args) {
    Steps steps(command.name, args.quiet);
    RecoveryOptions options;
    options.input = args.input;
    options.output = args.output;
    options.keep_exterior = args.keep_exterior;
    options.allow_open = args.allow_open;
    options.deep_flips = args.deep_flips;
    options.retries = args.retries;
    options.threads = args.threads;
    options.refine = command.refine;
    options.size = args.size;
    options.growth = args.growth;
    const RunDescription run{command.name, options, args.triangulate};
    RecoveryOutcome outcome;
    io::SurfaceMesh surface;
    steps.begin("reading", true);
    io::ReadOptions read_options;
    read_options.triangulate_polygons = args.triangulate;
    const io::Status read = io::read_surface(args.input, surface, read_options);
    if (read.ok()) {
        outcome = run_recovery(surface, options, steps);
    } else {
        outcome.exit_code = exit_code_for(read.kind);
        outcome.error = read.message;
    }
    steps.end();
    if (!args.quiet && outcome.exit_code == kExitOk) {
        std::printf("cbr %s: %s -> %s: %zu points, %zu tetrahedra\n", command.name, args.input.c_str(),
                    args.output.c_str(), outcome.points, outcome.tets);
    }
    // Table I also when the recovery itself failed: it says how far it got.
    if (!args.quiet && outcome.has_table_one) print_table_one(stdout, outcome.table_one);
    if (!args.quiet && outcome.has_refine) print_refine(stdout, outcome.refine);
    if (!args.quiet && outcome.has_quality) print_table_two(stdout, outcome.quality);
    return finish_run(run, args.json, outcome, steps);
}

}  // namespace

int run_volume_command(int argc, char** argv, const VolumeCommand& command) {
    try {
        VolumeArgs args;
        const int parsed = parse_args(argc, argv, command, args);
        return parsed != kContinue ? parsed : run(command, args);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "cbr %s: out of memory\n", command.name);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cbr %s: internal error: %s\n", command.name, e.what());
    }
    return kExitInternal;
}

}  // namespace cbr::cli

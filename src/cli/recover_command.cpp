#include "cli/recover_command.hpp"
#include "cli/output_options.hpp"

#include <cbr/cbr.h>

#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "cli/exit_codes.hpp"
#include "cli/recovery_run.hpp"
#include "cli/run_report.hpp"
#include "cli/steps.hpp"
#include "cli/table_one.hpp"
#include "cli/table_two.hpp"
#include "io/read_surface.hpp"
#include "io/write_volume.hpp"

namespace cbr::cli {
namespace {

constexpr int kContinue = -1;

struct RecoverArgs : OutputOptions {
    std::string input;
    bool keep_exterior = false;
    bool allow_open = false;
};

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "usage: cbr recover IN -o OUT [--json FILE] [--keep-exterior] [--allow-open] [-q]\n"
                 "\n"
                 "Tetrahedralizes the points of the surface IN (OFF, OBJ, STL, PLY, .smesh,\n"
                 ".poly, .mesh) and recovers every one of its triangles as a face, without\n"
                 "adding any point on the surface (Du & Wang 2004). Writes the tetrahedra of\n"
                 "the bounded regions to OUT (%s, by extension) and prints\n"
                 "the paper's Table I (recovery) and Table II (quality q = 3 r_in / r_circ,\n"
                 "1 for the regular tetrahedron; per region when there are several). The\n"
                 ".vtu output holds q per tetrahedron (cell data \"quality\").\n"
                 "\n"
                 "  -o OUT           the volume mesh to write (required)\n"
                 "  --json FILE      also write the run and both tables as JSON (written\n"
                 "                   for failed runs too, with their status and error)\n"
                 "  --keep-exterior  also write the exterior tetrahedra (region 0)\n"
                 "  --allow-open     recover an open surface too (its faces are recovered,\n"
                 "                   but it bounds no region: use with --keep-exterior)\n"
                 "  -q               print nothing but errors (and no progress line)\n"
                 "\n"
                 "A progress line is shown on stderr for steps longer than a second when\n"
                 "stderr is a terminal. CBR_TIMING=1 in the environment prints the time of\n"
                 "each step on stderr.\n"
                 "\n"
                 "exit codes: 0 success; 1 usage; 2 invalid input (a file that does not\n"
                 "parse, or a surface that cannot be recovered: cbr check says why); 3\n"
                 "recovery failure; 4 I/O (missing or unreadable input, unknown extension,\n"
                 "an output that cannot be written); 5 internal error.\n",
                 io::volume_extensions());
}

int parse_args(int argc, char** argv, RecoverArgs& args) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help") {
            print_help(stdout);
            return kExitOk;
        }
        int error = kContinue;
        if (take_output_option("recover", argc, argv, i, args, error)) {
            if (error != kContinue) return error;
        } else if (a == "--keep-exterior") {
            args.keep_exterior = true;
        } else if (a == "--allow-open") {
            args.allow_open = true;
        } else if (!a.empty() && a[0] == '-') {
            return usage_error("recover", "unknown option '" + a + "'");
        } else if (!args.input.empty()) {
            return usage_error("recover", "one input file only");
        } else {
            args.input = a;
        }
    }
    if (args.input.empty()) return usage_error("recover", "no input file");
    if (args.output.empty()) return usage_error("recover", "no output file (-o OUT)");
    return check_output_options("recover", args);
}

int recover(const RecoverArgs& args) {
    Steps steps("recover", args.quiet);
    const RunDescription run{"recover", args.input, args.output};
    RecoveryOutcome outcome;
    io::SurfaceMesh surface;
    steps.begin("reading", true);
    const io::Status read = io::read_surface(args.input, surface);
    if (read.ok()) {
        RecoveryOptions options;
        options.input = args.input;
        options.output = args.output;
        options.keep_exterior = args.keep_exterior;
        options.allow_open = args.allow_open;
        outcome = run_recovery(surface, options, steps);
    } else {
        outcome.exit_code = exit_code_for(read.kind);
        outcome.error = read.message;
    }
    steps.end();
    if (!args.quiet && outcome.exit_code == kExitOk) {
        std::printf("cbr recover: %s -> %s: %zu points, %zu tetrahedra\n", args.input.c_str(), args.output.c_str(),
                    outcome.points, outcome.tets);
    }
    // Table I also when the recovery itself failed: it says how far it got.
    if (!args.quiet && outcome.has_table_one) print_table_one(stdout, outcome.table_one);
    if (!args.quiet && outcome.has_quality) print_table_two(stdout, outcome.quality);
    return finish_run(run, args.json, outcome, steps);
}

}  // namespace

int run_recover(int argc, char** argv) {
    try {
        RecoverArgs args;
        const int parsed = parse_args(argc, argv, args);
        return parsed != kContinue ? parsed : recover(args);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "cbr recover: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cbr recover: internal error: %s\n", e.what());
    }
    return kExitInternal;
}

}  // namespace cbr::cli

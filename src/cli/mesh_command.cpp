#include "cli/mesh_command.hpp"
#include "cli/output_options.hpp"

#include <cbr/cbr.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

struct MeshArgs : OutputOptions {
    std::string input;
    double size = 0;
    bool keep_exterior = false;
    bool allow_open = false;
};

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "usage: cbr mesh IN -o OUT [--size H] [--json FILE] [--keep-exterior] [--allow-open] [-q]\n"
                 "\n"
                 "Tetrahedralizes the inside of the surface IN (OFF, OBJ, STL, PLY, .smesh,\n"
                 ".poly, .mesh): boundary recovery as in cbr recover (every triangle a face,\n"
                 "no point added on the surface), then points inserted inside the bounded\n"
                 "regions until the tetrahedra have the target size and shape, then flips\n"
                 "and smoothing (Du & Wang 2004, section 6). The surface stays exactly the\n"
                 "input. Writes the tetrahedra of the bounded regions to OUT (%s, by\n"
                 "extension) and prints the paper's Table I, the refinement counts and\n"
                 "Table II (quality q = 3 r_in / r_circ, 1 for the regular tetrahedron).\n"
                 "\n"
                 "  -o OUT           the volume mesh to write (required)\n"
                 "  --size H         target edge length inside (H > 0): the smaller of H and\n"
                 "                   the size of the surface triangles carried inside;\n"
                 "                   default: from the surface alone\n"
                 "  --json FILE      also write the run and the tables as JSON (written for\n"
                 "                   failed runs too, with their status and error)\n"
                 "  --keep-exterior  also write the exterior tetrahedra (region 0; never\n"
                 "                   refined)\n"
                 "  --allow-open     accept an open surface (it bounds no region: nothing is\n"
                 "                   refined)\n"
                 "  -q               print nothing but errors (and no progress line)\n"
                 "\n"
                 "exit codes: 0 success; 1 usage; 2 invalid input (a file that does not\n"
                 "parse, or a surface that cannot be recovered: cbr check says why); 3\n"
                 "recovery failure; 4 I/O (missing or unreadable input, unknown extension,\n"
                 "an output that cannot be written); 5 internal error.\n",
                 io::volume_extensions());
}

bool parse_size(const char* text, double& size) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text, &end);
    if (errno != 0 || end == text || *end != '\0' || !std::isfinite(v) || !(v > 0)) return false;
    size = v;
    return true;
}

int parse_args(int argc, char** argv, MeshArgs& args) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help") {
            print_help(stdout);
            return kExitOk;
        }
        int error = kContinue;
        if (take_output_option("mesh", argc, argv, i, args, error)) {
            if (error != kContinue) return error;
        } else if (a == "--size") {
            if (i + 1 >= argc) return usage_error("mesh", "--size needs a length");
            if (!parse_size(argv[++i], args.size))
                return usage_error("mesh", std::string("--size needs a finite length > 0, not '") + argv[i] + "'");
        } else if (a == "--keep-exterior") {
            args.keep_exterior = true;
        } else if (a == "--allow-open") {
            args.allow_open = true;
        } else if (!a.empty() && a[0] == '-') {
            return usage_error("mesh", "unknown option '" + a + "'");
        } else if (!args.input.empty()) {
            return usage_error("mesh", "one input file only");
        } else {
            args.input = a;
        }
    }
    if (args.input.empty()) return usage_error("mesh", "no input file");
    if (args.output.empty()) return usage_error("mesh", "no output file (-o OUT)");
    return check_output_options("mesh", args);
}

void print_refine(std::FILE* out, const RefineSummary& r) {
    std::fprintf(out, "Mesh generation (Du & Wang 2004, section 6)\n");
    std::fprintf(out, "  %-36s%12.0f\n", "field points inserted", r.field_points);
    std::fprintf(out, "  %-36s%12.0f\n", "quality flips", r.flips);
    std::fprintf(out, "  time: refinement %.3f s\n", r.seconds);
}

int mesh(const MeshArgs& args) {
    Steps steps("mesh", args.quiet);
    const RunDescription run{"mesh", args.input, args.output};
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
        options.refine = true;
        options.size = args.size;
        outcome = run_recovery(surface, options, steps);
    } else {
        outcome.exit_code = exit_code_for(read.kind);
        outcome.error = read.message;
    }
    steps.end();
    if (!args.quiet && outcome.exit_code == kExitOk) {
        std::printf("cbr mesh: %s -> %s: %zu points, %zu tetrahedra\n", args.input.c_str(), args.output.c_str(),
                    outcome.points, outcome.tets);
    }
    if (!args.quiet && outcome.has_table_one) print_table_one(stdout, outcome.table_one);
    if (!args.quiet && outcome.has_refine) print_refine(stdout, outcome.refine);
    if (!args.quiet && outcome.has_quality) print_table_two(stdout, outcome.quality);
    return finish_run(run, args.json, outcome, steps);
}

}  // namespace

int run_mesh(int argc, char** argv) {
    try {
        MeshArgs args;
        const int parsed = parse_args(argc, argv, args);
        return parsed != kContinue ? parsed : mesh(args);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "cbr mesh: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cbr mesh: internal error: %s\n", e.what());
    }
    return kExitInternal;
}

}  // namespace cbr::cli

#include "cli/demo_command.hpp"
#include "cli/output_options.hpp"

#include <cbr/cbr.h>

#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "cli/demo_geometry.hpp"
#include "cli/exit_codes.hpp"
#include "cli/recovery_run.hpp"
#include "cli/run_report.hpp"
#include "cli/steps.hpp"
#include "cli/table_one.hpp"
#include "cli/table_two.hpp"
#include "io/write_volume.hpp"

namespace cbr::cli {
namespace {

constexpr int kContinue = -1;
constexpr const char* kInputName = "nine-sphere box (built-in)";

struct DemoArgs : OutputOptions {};

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "usage: cbr demo [-o OUT] [--json FILE] [-q]\n"
                 "\n"
                 "Builds the paper's Example 1 in code (Du & Wang 2004: a box [0,3]x[0,3]x[0,1]\n"
                 "holding nine spheres, every sphere meshed on both sides), tetrahedralizes\n"
                 "its points, recovers its triangles and prints Table I (recovery) and\n"
                 "Table II (quality q = 3 r_in / r_circ, per region).\n"
                 "\n"
                 "  -o OUT       write the recovered mesh, in the format its extension\n"
                 "               names (%s)\n"
                 "  --json FILE  also write the run and both tables as JSON\n"
                 "  -q           print nothing but errors\n"
                 "\n"
                 "exit codes: as for cbr recover (cbr --help).\n",
                 io::volume_extensions());
}

int parse_args(int argc, char** argv, DemoArgs& args) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help") {
            print_help(stdout);
            return kExitOk;
        }
        int error = kContinue;
        if (take_output_option("demo", argc, argv, i, args, error)) {
            if (error != kContinue) return error;
            continue;
        }
        return usage_error("demo", "unknown argument '" + a + "'");
    }
    return check_output_options("demo", args);
}

io::SurfaceMesh demo_surface() {
    DemoSurface d = nine_sphere_box();
    io::SurfaceMesh s;
    s.xyz = std::move(d.xyz);
    s.tris = std::move(d.tris);
    s.labels = std::move(d.labels);
    return s;
}

int demo(const DemoArgs& args) {
    Steps steps("demo", args.quiet);
    steps.begin("building the surface");
    const io::SurfaceMesh s = demo_surface();
    RecoveryOptions options;
    options.input = kInputName;
    options.output = args.output;
    const RecoveryOutcome outcome = run_recovery(s, options, steps);
    steps.end();
    if (!args.quiet) {
        std::printf("cbr demo: Delaunay tetrahedralization of the nine-sphere box (Du & Wang 2004, Example 1)\n");
        std::printf("  surface: %zu points, %zu triangles (box + 9 spheres)\n", s.num_points(), s.num_triangles());
        if (outcome.has_table_one) {
            std::printf("  Delaunay: %zu points, %lld tetrahedra in %.3f s\n", s.num_points(),
                        static_cast<long long>(outcome.delaunay_tets), outcome.table_one.delaunay_seconds);
        }
        if (outcome.has_quality) {
            std::printf("  recovery: every surface triangle is a face; %zu tetrahedra in %.0f bounded regions\n",
                        outcome.tets, outcome.table_one.region_count - 1);
        }
        if (outcome.written) std::printf("  written: %s\n", args.output.c_str());
        if (outcome.has_table_one) print_table_one(stdout, outcome.table_one);
        if (outcome.has_quality) print_table_two(stdout, outcome.quality);
    }
    return finish_run({"demo", options}, args.json, outcome, steps);
}

}  // namespace

int run_demo(int argc, char** argv) {
    try {
        DemoArgs args;
        const int parsed = parse_args(argc, argv, args);
        return parsed != kContinue ? parsed : demo(args);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "cbr demo: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cbr demo: internal error: %s\n", e.what());
    }
    return kExitInternal;
}

}  // namespace cbr::cli

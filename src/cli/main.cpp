// The cbr command. It uses the public C API only, like any other user.
#include <cbr/cbr.h>

#include <cstdio>
#include <string>

#include "cli/check_command.hpp"
#include "cli/demo_command.hpp"
#include "cli/exit_codes.hpp"
#include "cli/mesh_command.hpp"
#include "cli/recover_command.hpp"

namespace {

using cbr::cli::kExitOk;
using cbr::cli::kExitUsage;

void print_usage(std::FILE* out) {
    std::fputs(
        "usage: cbr <command> [options]\n"
        "\n"
        "commands:\n"
        "  check IN    report what would stop a boundary recovery of the surface IN:\n"
        "              open edges, duplicate points, zero-area, duplicate and\n"
        "              intersecting triangles, ...; also non-manifold edges and\n"
        "              vertices, orientation, components, bounding box\n"
        "              (cbr check --help; --allow-open accepts open surfaces)\n"
        "  recover IN -o OUT [--json FILE]\n"
        "              Delaunay tetrahedralization of the points of IN and\n"
        "              recovery of its triangles without adding points on them;\n"
        "              writes OUT (.mesh, .vtu, .msh, .node/.ele/.face) and prints\n"
        "              the paper's Table I and Table II (cbr recover --help)\n"
        "  mesh IN -o OUT [--size H] [--growth R] [--json FILE]\n"
        "              full mesh generation: recover as above, then fill the inside\n"
        "              with points (target edge length H, default from the surface)\n"
        "              and improve the elements; same outputs and tables\n"
        "              (cbr mesh --help)\n"
        "  demo [-o OUT] [--json FILE]\n"
        "              tetrahedralize the built-in example (the paper's Example 1:\n"
        "              a box holding nine spheres) and print what was done\n"
        "  --version   print the library version\n"
        "  --help      this text\n"
        "\n"
        "exit codes: 0 success; 1 usage (bad command line); 2 invalid input (a\n"
        "file that does not parse, or a surface that cannot be recovered); 3\n"
        "recovery failure; 4 I/O (missing or\n"
        "unreadable file, unknown extension, an output that cannot be written);\n"
        "5 internal error.\n",
        out);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        print_usage(stderr);
        return kExitUsage;
    }
    const std::string command = argv[1];
    if (command == "--version") {
        std::printf("cbr %s\n", cbr_version());
        return kExitOk;
    }
    if (command == "--help" || command == "-h") {
        print_usage(stdout);
        return kExitOk;
    }
    if (command == "demo") return cbr::cli::run_demo(argc - 1, argv + 1);
    if (command == "check") return cbr::cli::run_check(argc - 1, argv + 1);
    if (command == "recover") return cbr::cli::run_recover(argc - 1, argv + 1);
    if (command == "mesh") return cbr::cli::run_mesh(argc - 1, argv + 1);
    std::fprintf(stderr, "cbr: unknown command '%s' (try cbr --help)\n", command.c_str());
    return kExitUsage;
}

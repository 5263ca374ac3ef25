// The cbr command. It uses the public C API only, like any other user.
#include <cbr/cbr.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli/check_command.hpp"
#include "cli/demo_geometry.hpp"
#include "cli/exit_codes.hpp"
#include "cli/recover_command.hpp"
#include "cli/table_one.hpp"

namespace {

using cbr::cli::exit_code_for;
using cbr::cli::kExitOk;
using cbr::cli::kExitUsage;
using cbr::cli::print_table_one;

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
        "  recover IN -o OUT\n"
        "              Delaunay tetrahedralization of the points of IN and\n"
        "              recovery of its triangles without adding points on them;\n"
        "              writes OUT (.mesh, .vtu, .msh, .node/.ele/.face) and the\n"
        "              paper's Table I (cbr recover --help)\n"
        "  demo        tetrahedralize the built-in example (the paper's Example 1:\n"
        "              a box holding nine spheres) and print what was done\n"
        "  --version   print the library version\n"
        "  --help      this text\n"
        "\n"
        "exit codes: 0 success; 1 usage (bad command line); 2 invalid input (a file\n"
        "that does not parse, or a surface that cannot be recovered); 3 recovery\n"
        "failure; 4 I/O (missing or unreadable file, unknown extension); 5 internal\n"
        "error.\n",
        out);
}

int run_demo() {
    const cbr::cli::DemoSurface s = cbr::cli::nine_sphere_box();
    const auto n = static_cast<std::int64_t>(s.xyz.size() / 3);
    std::printf("cbr demo: Delaunay tetrahedralization of the nine-sphere box (Du & Wang 2004, Example 1)\n");
    std::printf("  surface: %lld points, %zu triangles (box + 9 spheres)\n", static_cast<long long>(n),
                s.tris.size() / 3);
    cbr_mesh* mesh = nullptr;
    int status = cbr_mesh_create(&mesh);
    if (status != CBR_OK) {
        std::fprintf(stderr, "cbr: %s\n", cbr_status_string(status));
        return exit_code_for(status);
    }
    const auto start = std::chrono::steady_clock::now();
    status = cbr_mesh_insert_points(mesh, n, s.xyz.data());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (status != CBR_OK) {
        std::fprintf(stderr, "cbr: %s\n", cbr_mesh_last_error(mesh));
        cbr_mesh_destroy(mesh);
        return exit_code_for(status);
    }
    std::printf("  Delaunay: %lld points, %lld tetrahedra in %.3f s\n",
                static_cast<long long>(cbr_mesh_point_count(mesh)), static_cast<long long>(cbr_mesh_tet_count(mesh)),
                seconds);
    status = cbr_mesh_recover_faces(mesh, static_cast<std::int64_t>(s.tris.size() / 3), s.tris.data(), s.labels.data());
    if (status == CBR_OK) {
        double regions = 0;
        cbr_mesh_get_stat(mesh, CBR_STAT_REGION_COUNT, &regions);
        std::printf("  recovery: every surface triangle is a face; %lld tetrahedra in %.0f bounded regions\n",
                    static_cast<long long>(cbr_mesh_tet_count(mesh)), regions - 1);
    } else {
        std::printf("  recovery: %s\n", cbr_mesh_last_error(mesh));
    }
    print_table_one(mesh);
    cbr_mesh_destroy(mesh);
    return kExitOk;
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
    if (command == "demo") return run_demo();
    if (command == "check") return cbr::cli::run_check(argc - 1, argv + 1);
    if (command == "recover") return cbr::cli::run_recover(argc - 1, argv + 1);
    std::fprintf(stderr, "cbr: unknown command '%s' (try cbr --help)\n", command.c_str());
    return kExitUsage;
}

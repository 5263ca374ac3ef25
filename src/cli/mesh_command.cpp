#include "cli/mesh_command.hpp"

#include <cbr/cbr.h>

#include <cstdio>
#include <cstring>

#include "cli/exit_codes.hpp"

namespace cbr::cli {
namespace {

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "usage: cbr mesh IN -o OUT [--size H]\n"
                 "\n"
                 "NOT AVAILABLE YET in libcbr %s: every run exits with code 1.\n"
                 "\n"
                 "Will tetrahedralize the inside of the surface IN: boundary recovery as in\n"
                 "cbr recover, then points inserted inside until the tetrahedra have size\n"
                 "about H (--size; default: from the surface's edge lengths), and their\n"
                 "quality improved. Until then, cbr recover IN -o OUT gives the tetrahedra\n"
                 "of the recovered boundary, with no interior point.\n",
                 cbr_version());
}

}  // namespace

int run_mesh(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "-h") == 0 || std::strcmp(argv[i], "--help") == 0) {
            print_help(stdout);
            return kExitOk;
        }
    }
    std::fprintf(stderr, "cbr mesh: full mesh generation is not available yet in libcbr %s (see cbr recover)\n",
                 cbr_version());
    return kExitUsage;
}

}  // namespace cbr::cli

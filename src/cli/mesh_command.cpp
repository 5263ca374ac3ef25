#include "cli/mesh_command.hpp"

#include <cstdio>

#include "cli/volume_command.hpp"
#include "io/write_volume.hpp"

namespace cbr::cli {
namespace {

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "usage: cbr mesh IN -o OUT [--size H] [--growth R] [--json FILE]\n"
                 "       [--keep-exterior] [--allow-open] [--triangulate] [--no-deep-flips]\n"
                 "       [--no-retries] [--threads N] [-q]\n"
                 "\n"
                 "Tetrahedralizes the inside of the surface IN (OFF, OBJ, STL, PLY, .smesh,\n"
                 ".poly, .mesh): boundary recovery as in cbr recover (every triangle a face,\n"
                 "no point added on the surface), then points inserted inside the bounded\n"
                 "regions until the tetrahedra have the target size and shape, then flips\n"
                 "and smoothing (Du & Wang 2004, section 6). The surface stays exactly the\n"
                 "input. Writes the tetrahedra of the bounded regions to OUT, in the\n"
                 "format its extension names (%s),\n"
                 "and prints the paper's Table I, the refinement counts and Table II\n"
                 "(quality q = 3 r_in / r_circ, 1 for the regular tetrahedron).\n"
                 "\n"
                 "  -o OUT           the volume mesh to write (required)\n"
                 "  --size H         target edge length inside (H > 0): the smaller of H and\n"
                 "                   the size of the surface triangles carried inside;\n"
                 "                   default: from the surface alone\n"
                 "  --growth R       let the size grow by R per unit length away from the\n"
                 "                   surface (0 <= R <= 100): larger R, fewer and larger\n"
                 "                   tetrahedra inside; 0: the surface's size carried\n"
                 "                   inside; default 0.3\n"
                 "  --json FILE      also write the run and the tables as JSON (written for\n"
                 "                   failed runs too, with their status and error)\n"
                 "  --keep-exterior  also write the exterior tetrahedra (region 0; never\n"
                 "                   refined)\n"
                 "  --allow-open     accept an open surface (it bounds no region: nothing is\n"
                 "                   refined)\n"
                 "  --triangulate    split faces with more than 3 corners into triangle fans\n"
                 "                   (as in cbr recover)\n"
                 "  --no-deep-flips  skip the deepest flip searches of recovery (as in cbr\n"
                 "                   recover)\n"
                 "  --no-retries     no further recovery attempts after a failure (as in\n"
                 "                   cbr recover)\n"
                 "  --threads N      threads for the passes that only read the whole mesh\n"
                 "                   (as in cbr recover) and for the field points, the\n"
                 "                   smoothing and the quality flips of the refinement\n"
                 "                   (0, the default: the hardware's)\n"
                 "  -q               print nothing but errors (and no progress line)\n"
                 "\n"
                 "exit codes: 0 success; 1 usage; 2 invalid input (a file that does not\n"
                 "parse, or a surface that cannot be recovered: cbr check says why); 3\n"
                 "recovery failure; 4 I/O (missing or unreadable input, unknown extension,\n"
                 "an output that cannot be written); 5 internal error.\n",
                 io::volume_extensions());
}

}  // namespace

int run_mesh(int argc, char** argv) { return run_volume_command(argc, argv, {"mesh", print_help, true}); }

}  // namespace cbr::cli

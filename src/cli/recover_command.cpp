#include "cli/recover_command.hpp"

#include <cstdio>

#include "cli/volume_command.hpp"
#include "io/write_volume.hpp"

namespace cbr::cli {
namespace {

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "usage: cbr recover IN -o OUT [--json FILE] [--keep-exterior] [--allow-open]\n"
                 "       [--triangulate] [--no-deep-flips] [--no-retries] [--threads N] [-q]\n"
                 "\n"
                 "Tetrahedralizes the points of the surface IN (OFF, OBJ, STL, PLY, .smesh,\n"
                 ".poly, .mesh) and recovers every one of its triangles as a face, without\n"
                 "adding any point on the surface (Du & Wang 2004). Writes the tetrahedra of\n"
                 "the bounded regions to OUT, in the format its extension names\n"
                 "(%s), and prints\n"
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
                 "  --triangulate    split faces with more than 3 corners into fans of\n"
                 "                   triangles from their first corner (otherwise such a\n"
                 "                   face is a parse error); a fan of a polygon that is not\n"
                 "                   convex and planar can overlap, which the input checks\n"
                 "                   then reject\n"
                 "  --no-deep-flips  skip the deepest flip searches: faster on surfaces whose\n"
                 "                   faces flips find hard, for more Steiner points\n"
                 "  --no-retries     report a failure of the first attempt at once, without\n"
                 "                   the attempts from other flip states and inside an\n"
                 "                   enclosing box (a failure then takes one attempt's time)\n"
                 "  --threads N      threads for the passes that only read the whole mesh\n"
                 "                   (validity checks, Table II beside writing OUT): 0\n"
                 "                   (default) as many as the hardware runs at once; the\n"
                 "                   results are the same with any number\n"
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

}  // namespace

int run_recover(int argc, char** argv) { return run_volume_command(argc, argv, {"recover", print_help, false}); }

}  // namespace cbr::cli

// `cbr recover IN -o OUT [--json FILE]`: Delaunay tetrahedralization of a
// surface's points, constrained boundary recovery of its triangles, the
// volume mesh written to OUT (format by extension), the paper's Table I
// and Table II printed and, with --json, written as JSON (run_report.hpp).
#pragma once

namespace cbr::cli {

// argv[0] is "recover". Returns the process exit code.
int run_recover(int argc, char** argv);

}  // namespace cbr::cli

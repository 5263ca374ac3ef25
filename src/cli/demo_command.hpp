// `cbr demo [-o OUT] [--json FILE] [-q]`: the paper's Example 1 (a box
// holding nine spherical inclusions, demo_geometry.hpp) tetrahedralized and
// recovered, its Table I and Table II printed, the mesh written to OUT when
// given.
#pragma once

namespace cbr::cli {

// argv[0] is "demo". Returns the process exit code.
int run_demo(int argc, char** argv);

}  // namespace cbr::cli

// `cbr mesh IN -o OUT [--size H]`: boundary recovery followed by full mesh
// generation (Du & Wang 2004, §6: field points, optimisation) through
// cbr_mesh_refine; the same outputs, tables and --json as cbr recover.
#pragma once

namespace cbr::cli {

// argv[0] is "mesh". Returns the process exit code.
int run_mesh(int argc, char** argv);

}  // namespace cbr::cli

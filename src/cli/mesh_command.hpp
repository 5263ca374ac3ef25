// `cbr mesh IN -o OUT [--size H]`: boundary recovery followed by full mesh
// generation (interior points, quality improvement). Mesh generation is not
// in libcbr yet: until it is, the command says so and exits with code 1
// (usage), as documented in its --help and in README, "The cbr command".
#pragma once

namespace cbr::cli {

// argv[0] is "mesh". Returns the process exit code.
int run_mesh(int argc, char** argv);

}  // namespace cbr::cli

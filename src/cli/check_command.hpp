// `cbr check IN`: reads a surface and reports what would stop a boundary
// recovery (libcbr's exact checks through the C API, plus the command's own
// combinatorial checks), with indices. Exit codes: exit_codes.hpp.
#pragma once

#include <cstdio>

namespace cbr::cli {

// argv[0] is "check"; the arguments follow.
int run_check(int argc, char** argv);

void print_check_help(std::FILE* out);

}  // namespace cbr::cli

// The paper's Table II (element quality, Du & Wang 2004) printed on stdout:
// the whole mesh, then one compact line per region when there are several.
#pragma once

#include <cstdio>

#include "cli/quality.hpp"

namespace cbr::cli {

void print_table_two(std::FILE* out, const QualityReport& report);

}  // namespace cbr::cli

// The paper's Table I (recovery statistics), printed from a cbr_mesh.
#pragma once

#include <cbr/cbr.h>

namespace cbr::cli {

void print_table_one(cbr_mesh* m);

}  // namespace cbr::cli

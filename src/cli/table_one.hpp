// The paper's Table I (recovery statistics, Du & Wang 2004): read from a
// cbr_mesh through cbr_mesh_get_stat, printed on stdout.
#pragma once

#include <cbr/cbr.h>

#include <cstdio>

namespace cbr::cli {

struct TableOne {
    double total_vertices = 0;      // CBR_STAT_TOTAL_VERTICES
    double boundary_vertices = 0;   // CBR_STAT_BOUNDARY_VERTICES
    double missing_faces = 0;       // CBR_STAT_MISSING_FACES
    double recovered_by_flips = 0;  // CBR_STAT_FACES_RECOVERED_BY_FLIPS
    double conforming_points = 0;   // CBR_STAT_CONFORMING_POINTS
    double steiner_generated = 0;   // CBR_STAT_STEINER_GENERATED
    double steiner_remaining = 0;   // CBR_STAT_STEINER_REMAINING
    double steiner_inside = 0;      // CBR_STAT_STEINER_INSIDE (bounded regions only)
    double region_count = 0;        // CBR_STAT_REGION_COUNT (exterior included)
    double delaunay_seconds = 0;    // CBR_STAT_DELAUNAY_SECONDS
    double recovery_seconds = 0;    // CBR_STAT_RECOVERY_SECONDS
    double total_seconds = 0;       // CBR_STAT_TOTAL_SECONDS
};

TableOne read_table_one(const cbr_mesh* m);

void print_table_one(std::FILE* out, const TableOne& t);

}  // namespace cbr::cli

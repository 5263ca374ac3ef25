#include "cli/table_one.hpp"

namespace cbr::cli {

TableOne read_table_one(const cbr_mesh* m) {
    auto stat = [m](int key) {
        double v = 0;
        cbr_mesh_get_stat(m, key, &v);
        return v;
    };
    TableOne t;
    t.total_vertices = stat(CBR_STAT_TOTAL_VERTICES);
    t.boundary_vertices = stat(CBR_STAT_BOUNDARY_VERTICES);
    t.missing_faces = stat(CBR_STAT_MISSING_FACES);
    t.recovered_by_flips = stat(CBR_STAT_FACES_RECOVERED_BY_FLIPS);
    t.conforming_points = stat(CBR_STAT_CONFORMING_POINTS);
    t.steiner_generated = stat(CBR_STAT_STEINER_GENERATED);
    t.steiner_remaining = stat(CBR_STAT_STEINER_REMAINING);
    t.steiner_inside = stat(CBR_STAT_STEINER_INSIDE);
    t.region_count = stat(CBR_STAT_REGION_COUNT);
    t.delaunay_seconds = stat(CBR_STAT_DELAUNAY_SECONDS);
    t.recovery_seconds = stat(CBR_STAT_RECOVERY_SECONDS);
    t.total_seconds = stat(CBR_STAT_TOTAL_SECONDS);
    return t;
}

void print_table_one(std::FILE* out, const TableOne& t) {
    std::fprintf(out, "Recovery statistics (Du & Wang 2004, Table I)\n");
    std::fprintf(out, "  total vertices                      %12.0f\n", t.total_vertices);
    std::fprintf(out, "  boundary vertices                   %12.0f\n", t.boundary_vertices);
    std::fprintf(out, "  faces missing after Delaunay        %12.0f\n", t.missing_faces);
    std::fprintf(out, "  recovered by flips                  %12.0f\n", t.recovered_by_flips);
    std::fprintf(out, "  points added in conforming recovery %12.0f\n", t.conforming_points);
    std::fprintf(out, "  Steiner points generated inside     %12.0f\n", t.steiner_generated);
    std::fprintf(out, "  Steiner points remaining            %12.0f\n", t.steiner_remaining);
    std::fprintf(out, "  Steiner points inside the domain    %12.0f\n", t.steiner_inside);
    std::fprintf(out, "  regions (exterior included)         %12.0f\n", t.region_count);
    std::fprintf(out, "  time: Delaunay %.3f s, recovery %.3f s, total %.3f s (recovery %.1f%%)\n",
                 t.delaunay_seconds, t.recovery_seconds, t.total_seconds,
                 t.total_seconds > 0 ? 100 * t.recovery_seconds / t.total_seconds : 0.0);
}

}  // namespace cbr::cli

#include "cli/table_one.hpp"

#include <cstdio>

namespace cbr::cli {

void print_table_one(cbr_mesh* m) {
    auto stat = [m](int key) {
        double v = 0;
        cbr_mesh_get_stat(m, key, &v);
        return v;
    };
    const double total = stat(CBR_STAT_TOTAL_SECONDS);
    std::printf("Recovery statistics (Du & Wang 2004, Table I)\n");
    std::printf("  total vertices                      %12.0f\n", stat(CBR_STAT_TOTAL_VERTICES));
    std::printf("  boundary vertices                   %12.0f\n", stat(CBR_STAT_BOUNDARY_VERTICES));
    std::printf("  faces missing after Delaunay        %12.0f\n", stat(CBR_STAT_MISSING_FACES));
    std::printf("  recovered by flips                  %12.0f\n", stat(CBR_STAT_FACES_RECOVERED_BY_FLIPS));
    std::printf("  points added in conforming recovery %12.0f\n", stat(CBR_STAT_CONFORMING_POINTS));
    std::printf("  Steiner points generated inside     %12.0f\n", stat(CBR_STAT_STEINER_GENERATED));
    std::printf("  Steiner points remaining            %12.0f\n", stat(CBR_STAT_STEINER_REMAINING));
    std::printf("  regions (exterior included)         %12.0f\n", stat(CBR_STAT_REGION_COUNT));
    std::printf("  time: Delaunay %.3f s, recovery %.3f s, total %.3f s (recovery %.1f%%)\n",
                stat(CBR_STAT_DELAUNAY_SECONDS), stat(CBR_STAT_RECOVERY_SECONDS), total,
                total > 0 ? 100 * stat(CBR_STAT_RECOVERY_SECONDS) / total : 0.0);
}

}  // namespace cbr::cli

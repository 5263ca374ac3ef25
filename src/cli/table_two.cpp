#include "cli/table_two.hpp"

#include <cmath>

namespace cbr::cli {
namespace {

// "%*.*f"; "%*.3g" for a value too small to show that way (a sliver's
// quality of 1e-20 is not 0.0000); "-" when v is NaN (no tetrahedron).
void put_number(std::FILE* out, int width, int decimals, double v) {
    if (std::isnan(v)) {
        std::fprintf(out, "%*s", width, "-");
    } else if (v != 0 && std::fabs(v) < 0.5 * std::pow(10.0, -decimals)) {
        std::fprintf(out, "%*.3g", width, v);
    } else {
        std::fprintf(out, "%*.*f", width, decimals, v);
    }
}

void row(std::FILE* out, const char* label, int decimals, double v, const char* unit) {
    std::fprintf(out, "  %-36s", label);
    put_number(out, 12, decimals, v);
    std::fprintf(out, "%s\n", std::isnan(v) ? "" : unit);
}

void region_line(std::FILE* out, const RegionQuality& r) {
    const QualityStats& s = r.stats;
    std::fprintf(out, "    region %d: %lld tets, q avg ", static_cast<int>(r.region), static_cast<long long>(s.tets));
    put_number(out, 0, 4, s.quality_average);
    std::fprintf(out, " min ");
    put_number(out, 0, 4, s.quality_min);
    std::fprintf(out, ", q>0.4 ");
    put_number(out, 0, 1, s.percent_above_0_4);
    std::fprintf(out, "%%, q<0.1 ");
    put_number(out, 0, 1, s.percent_below_0_1);
    std::fprintf(out, "%% (%lld at Steiner), dihedral ", static_cast<long long>(s.bad_touching_steiner));
    put_number(out, 0, 2, s.dihedral_min_deg);
    std::fprintf(out, "..");
    put_number(out, 0, 2, s.dihedral_max_deg);
    std::fprintf(out, " deg\n");
}

}  // namespace

void print_table_two(std::FILE* out, const QualityReport& report) {
    const QualityStats& s = report.all;
    std::fprintf(out, "Mesh quality (Du & Wang 2004, Table II; q = 3 r_in / r_circ, 1 = regular)\n");
    std::fprintf(out, "  %-36s%12lld\n", "tetrahedra", static_cast<long long>(s.tets));
    row(out, "average quality", 4, s.quality_average, "");
    row(out, "minimum quality", 4, s.quality_min, "");
    row(out, "elements with q > 0.4", 2, s.percent_above_0_4, " %");
    row(out, "elements with q < 0.1", 2, s.percent_below_0_1, " %");
    std::fprintf(out, "  %-36s%12lld\n", "q < 0.1 touching a Steiner point", static_cast<long long>(s.bad_touching_steiner));
    row(out, "minimum dihedral angle", 2, s.dihedral_min_deg, " deg");
    row(out, "maximum dihedral angle", 2, s.dihedral_max_deg, " deg");
    if (report.regions.empty()) return;
    std::fprintf(out, "  per region:\n");
    for (const RegionQuality& r : report.regions) region_line(out, r);
}

}  // namespace cbr::cli

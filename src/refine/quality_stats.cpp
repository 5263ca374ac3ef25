#include "refine/quality_stats.hpp"

#include <algorithm>
#include <limits>

#include "refine/tet_measures.hpp"

namespace cbr::refine {

std::vector<char> steiner_flags(const mesh::TetMesh& m, const std::vector<mesh::VertexId>& steiner) {
    std::vector<char> flags(m.vertex_count(), 0);
    for (mesh::VertexId v : steiner)
        if (v < flags.size()) flags[v] = 1;
    return flags;
}

QualityTable measure_quality(const mesh::TetMesh& m, const std::vector<std::int32_t>& region_of_slot,
                             const std::vector<mesh::VertexId>& steiner) {
    const std::vector<char> is_steiner = steiner_flags(m, steiner);
    QualityTable s;
    double sum = 0, q_min = std::numeric_limits<double>::infinity();
    double lo = 180, hi = 0;
    std::size_t above = 0, below = 0;
    for (mesh::TetId t = 0; t < m.slot_count() && t < region_of_slot.size(); ++t) {
        if (m.is_free(t) || m.is_ghost(t) || region_of_slot[t] <= 0) continue;
        const mesh::VertexId* v = m.vertices(t);
        const double* p[4] = {m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])};
        const double q = radius_ratio(p[0], p[1], p[2], p[3]);
        double dmin = 0, dmax = 0;
        dihedral_range(p[0], p[1], p[2], p[3], dmin, dmax);
        ++s.tets;
        sum += q;
        q_min = std::min(q_min, q);
        lo = std::min(lo, dmin);
        hi = std::max(hi, dmax);
        if (q > 0.4) ++above;
        if (q < 0.1) {
            ++below;
            if (has_flagged_corner(m, t, is_steiner)) ++s.bad_touching_steiner;
        }
    }
    if (s.tets == 0) return s;
    const auto n = static_cast<double>(s.tets);
    s.average = sum / n;
    s.minimum = q_min;
    s.percent_above_0_4 = 100.0 * static_cast<double>(above) / n;
    s.percent_below_0_1 = 100.0 * static_cast<double>(below) / n;
    s.dihedral_min_deg = lo;
    s.dihedral_max_deg = hi;
    return s;
}

}  // namespace cbr::refine

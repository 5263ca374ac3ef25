#include "refine/quality_stats.hpp"

#include <algorithm>
#include <limits>

#include "mesh/chunks.hpp"
#include "refine/tet_measures.hpp"

namespace cbr::refine {

std::vector<char> steiner_flags(const mesh::TetMesh& m, const std::vector<mesh::VertexId>& steiner) {
    std::vector<char> flags(m.vertex_count(), 0);
    for (mesh::VertexId v : steiner)
        if (v < flags.size()) flags[v] = 1;
    return flags;
}

namespace {

// What one chunk of the slots measured: the radius ratio of each of its
// tetrahedra (by slot, for the sum, which is taken in slot order), and
// the counts and extremes, which do not depend on the order.
struct ChunkTable {
    std::size_t tets = 0, above = 0, below = 0, bad_touching_steiner = 0;
    double q_min = std::numeric_limits<double>::infinity();
    double lo = 180, hi = 0;
};

}  // namespace

QualityTable measure_quality(const mesh::TetMesh& m, const std::vector<std::int32_t>& region_of_slot,
                             const std::vector<mesh::VertexId>& steiner, int threads) {
    const std::vector<char> is_steiner = steiner_flags(m, steiner);
    const std::size_t slots = std::min<std::size_t>(m.slot_count(), region_of_slot.size());
    const auto measured = [&](mesh::TetId t) { return !m.is_free(t) && !m.is_ghost(t) && region_of_slot[t] > 0; };
    std::vector<double> q_of(slots, 0.0);
    std::vector<ChunkTable> chunk(mesh::chunk_count(slots, threads));
    mesh::run_chunks(slots, chunk.size(), [&](std::size_t k, std::size_t begin, std::size_t end) {
        ChunkTable& c = chunk[k];
        for (auto t = static_cast<mesh::TetId>(begin); t < end; ++t) {
            if (!measured(t)) continue;
            const mesh::VertexId* v = m.vertices(t);
            const double* p[4] = {m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])};
            const double q = radius_ratio(p[0], p[1], p[2], p[3]);
            double dmin = 0, dmax = 0;
            dihedral_range(p[0], p[1], p[2], p[3], dmin, dmax);
            q_of[t] = q;
            ++c.tets;
            c.q_min = std::min(c.q_min, q);
            c.lo = std::min(c.lo, dmin);
            c.hi = std::max(c.hi, dmax);
            if (q > 0.4) ++c.above;
            if (q < 0.1) {
                ++c.below;
                if (has_flagged_corner(m, t, is_steiner)) ++c.bad_touching_steiner;
            }
        }
    });
    QualityTable s;
    ChunkTable all;
    for (const ChunkTable& c : chunk) {
        all.tets += c.tets;
        all.above += c.above;
        all.below += c.below;
        all.bad_touching_steiner += c.bad_touching_steiner;
        all.q_min = std::min(all.q_min, c.q_min);
        all.lo = std::min(all.lo, c.lo);
        all.hi = std::max(all.hi, c.hi);
    }
    if (all.tets == 0) return s;
    double sum = 0;  // in slot order, as one pass adds (the 0 of a slot not measured changes nothing)
    for (const double q : q_of) sum += q;
    s.tets = all.tets;
    s.bad_touching_steiner = all.bad_touching_steiner;
    const auto n = static_cast<double>(s.tets);
    s.average = sum / n;
    s.minimum = all.q_min;
    s.percent_above_0_4 = 100.0 * static_cast<double>(all.above) / n;
    s.percent_below_0_1 = 100.0 * static_cast<double>(all.below) / n;
    s.dihedral_min_deg = all.lo;
    s.dihedral_max_deg = all.hi;
    return s;
}

}  // namespace cbr::refine

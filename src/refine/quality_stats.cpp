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

// What one chunk of the slots measured in one region, or in all: the
// counts and extremes, which do not depend on the order (the sums of the
// radius ratios are taken in slot order, from q_of).
struct ChunkTable {
    std::size_t tets = 0, above = 0, below = 0, bad_touching_steiner = 0;
    double q_min = std::numeric_limits<double>::infinity();
    double lo = 180, hi = 0;

    void add(double q, double dmin, double dmax, bool at_steiner) {
        ++tets;
        q_min = std::min(q_min, q);
        lo = std::min(lo, dmin);
        hi = std::max(hi, dmax);
        if (q > 0.4) ++above;
        if (q < 0.1) {
            ++below;
            if (at_steiner) ++bad_touching_steiner;
        }
    }
    void merge(const ChunkTable& c) {
        tets += c.tets;
        above += c.above;
        below += c.below;
        bad_touching_steiner += c.bad_touching_steiner;
        q_min = std::min(q_min, c.q_min);
        lo = std::min(lo, c.lo);
        hi = std::max(hi, c.hi);
    }
    // The table, given the sum of the radius ratios.
    QualityTable table(double sum) const {
        QualityTable s;
        if (tets == 0) return s;
        s.tets = tets;
        s.bad_touching_steiner = bad_touching_steiner;
        const auto n = static_cast<double>(tets);
        s.average = sum / n;
        s.minimum = q_min;
        s.percent_above_0_4 = 100.0 * static_cast<double>(above) / n;
        s.percent_below_0_1 = 100.0 * static_cast<double>(below) / n;
        s.dihedral_min_deg = lo;
        s.dihedral_max_deg = hi;
        return s;
    }
};

}  // namespace

QualityTable measure_quality(const mesh::TetMesh& m, const std::vector<std::int32_t>& region_of_slot,
                             const std::vector<mesh::VertexId>& steiner, int threads,
                             std::vector<QualityTable>* by_region) {
    const std::vector<char> is_steiner = steiner_flags(m, steiner);
    const std::size_t slots = std::min<std::size_t>(m.slot_count(), region_of_slot.size());
    const auto measured = [&](mesh::TetId t) { return !m.is_free(t) && !m.is_ghost(t) && region_of_slot[t] > 0; };
    std::size_t regions = 0;  // 1 + the largest region measured (only with by_region)
    if (by_region)
        for (std::size_t t = 0; t < slots; ++t)
            if (measured(static_cast<mesh::TetId>(t)))
                regions = std::max(regions, static_cast<std::size_t>(region_of_slot[t]) + 1);
    std::vector<double> q_of(slots, 0.0);
    struct Chunk {
        ChunkTable all;
        std::vector<ChunkTable> region;
    };
    std::vector<Chunk> chunk(mesh::chunk_count(slots, threads), Chunk{ChunkTable{}, std::vector<ChunkTable>(regions)});
    mesh::run_chunks(slots, chunk.size(), [&](std::size_t k, std::size_t begin, std::size_t end) {
        Chunk& c = chunk[k];
        for (auto t = static_cast<mesh::TetId>(begin); t < end; ++t) {
            if (!measured(t)) continue;
            const mesh::VertexId* v = m.vertices(t);
            const double* p[4] = {m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])};
            const double q = radius_ratio(p[0], p[1], p[2], p[3]);
            double dmin = 0, dmax = 0;
            dihedral_range(p[0], p[1], p[2], p[3], dmin, dmax);
            q_of[t] = q;
            const bool at_steiner = q < 0.1 && has_flagged_corner(m, t, is_steiner);
            c.all.add(q, dmin, dmax, at_steiner);
            if (regions > 0) c.region[static_cast<std::size_t>(region_of_slot[t])].add(q, dmin, dmax, at_steiner);
        }
    });
    ChunkTable all;
    std::vector<ChunkTable> region(regions);
    for (const Chunk& c : chunk) {
        all.merge(c.all);
        for (std::size_t r = 0; r < regions; ++r) region[r].merge(c.region[r]);
    }
    // The sums in slot order, as one pass adds (the 0 of a slot not
    // measured changes nothing).
    double sum = 0;
    std::vector<double> region_sum(regions, 0.0);
    for (std::size_t t = 0; t < slots; ++t) {
        sum += q_of[t];
        if (regions > 0 && measured(static_cast<mesh::TetId>(t)))
            region_sum[static_cast<std::size_t>(region_of_slot[t])] += q_of[t];
    }
    if (by_region) {
        by_region->assign(regions, QualityTable{});
        for (std::size_t r = 0; r < regions; ++r) (*by_region)[r] = region[r].table(region_sum[r]);
    }
    return all.table(sum);
}

}  // namespace cbr::refine

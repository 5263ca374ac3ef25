#include "refine/field_points.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

#include "mesh/chunks.hpp"
#include "mesh/vertex_compaction.hpp"
#include "mesh/slot_pool.hpp"
#include "refine/field_refiner.hpp"
#include "refine/vertex_halves.hpp"

namespace cbr::refine {
namespace {

using mesh::TetId;
using mesh::VertexId;

// The field points in two halves (the quality flips' scheme,
// quality_flips.cpp), so that two threads (CBR_PARAM_THREADS) can insert at
// once and the mesh is the same whatever the number of threads. The
// vertices are split at the median (vertex_halves.hpp) and labelled; a
// tetrahedron is a half's when its four corners carry its label
// (HalfClaim). First the border, the tetrahedra of neither half, is refined
// on one thread, each new point labelled by its side of the median plane,
// until what is left across the plane meets the field (the first Delaunay
// tetrahedra of a surface are large: a half would have to leave every
// cavity that meets them). Then each half refines its own tetrahedra,
// queued in slot order, with its own queue, insertion scratch and slot
// pool; its points get its label, so the star of a cavity of the half's is
// the half's again. A tetrahedron whose refinement needs one not its own
// (a walk, a cavity or a correction that would enter it) is left for the
// border's refinement, which takes those last, on one thread. On
// common3d-igea the border's two parts insert 2.5% of the points.
// Why the halves never touch the same data: an insertion writes the
// tetrahedra of its cavity (the half's), the slots of its pool and the links
// of the tetrahedra across the cavity's boundary, which share three corners
// with it. It reads the half's tetrahedra and the corners (not the links) of
// their face neighbours, which have three corners in the half. A
// tetrahedron the other half writes has at least three corners there, so
// at most one here.
// Vertex ids: each round gives each half a range of ids taken ahead (the
// mesh's coordinates, the sizing field and the labels grown once, so no
// array grows under a thread) and a pool of slots; a half stops when its
// range or pool runs short, and when both have stopped, the ids used close
// up (half 1's after half 0's) and the unused ones go. So the points are
// numbered round by round, half 0's before half 1's, whatever the number of
// threads.
constexpr std::size_t kSlotsPerId = 8;  // a point adds about 6.3 tetrahedra net
// The ids of a round double up to this many per half: the pools' slots that
// a round leaves unused stay in the mesh until the renumbering after the
// field points (igea's peak memory 512 MB with no bound, 445 with this one,
// 390 when the halves' refiners also go before the border's last part;
// 364 with the field points on one refiner).
constexpr std::size_t kMostRoundIds = 16384;

// After a round: the ids taken ahead and left unused go, those used close
// up in order (half 0's, then half 1's) through mesh::compact_vertices_from,
// and the sizing field, the labels and the halves' queues and logs follow.
void close_up_ids(RefineContext& c, std::vector<std::uint8_t>& label,
                  std::array<std::unique_ptr<FieldRefiner>, 2>& halves, VertexId first) {
    std::vector<VertexId> none, kept;
    mesh::compact_vertices_from(c.m, first, none, &kept);  // kept[i]: the old id of first + i
    for (std::size_t i = 0; i < kept.size(); ++i) {
        c.size.set(static_cast<VertexId>(first + i), c.size.at(kept[i]));
        label[first + i] = label[kept[i]];
    }
    c.size.truncate(c.m.vertex_count());
    label.resize(c.m.vertex_count());
    const auto renumber = [&](VertexId v) {
        if (v < first) return v;
        return static_cast<VertexId>(first + (std::lower_bound(kept.begin(), kept.end(), v) - kept.begin()));
    };
    for (std::unique_ptr<FieldRefiner>& half : halves) half->renumber_queued(renumber);
}

void insert_in_halves(RefineContext& c, RefineStats& stats, FieldPointsLog* log) {
    mesh::TetMesh& m = c.m;
    const std::size_t at_start = stats.field_points;
    std::vector<VertexId> all(m.vertex_count());
    for (VertexId v = 0; v < all.size(); ++v) all[v] = v;
    MedianPlane plane;
    std::vector<std::uint8_t> label = median_halves(m, all, &plane);
    FieldRefiner border(c, stats);
    const std::size_t cap = border.point_cap();
    border.keep_to_border(&label, plane);
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (c.in_domain(t)) border.queue_tet(t);
    border.set_cap(cap);
    if (log) border.set_log(&log->insertions);
    border.run_queue();
    const std::size_t border_before = stats.field_points - at_start;
    border.keep_to_border(nullptr, plane);
    const std::size_t half_cap = cap - std::min(cap, stats.field_points);
    std::array<RefineStats, 2> half_stats;
    std::array<std::unique_ptr<FieldRefiner>, 2> halves;
    std::array<std::vector<TetChange>, 3> logs;  // the halves', the border's after them
    for (std::uint8_t h = 0; h < 2; ++h) {
        halves[h] = std::make_unique<FieldRefiner>(c, half_stats[h]);
        halves[h]->queue_claimed({&label, h});
        if (log) halves[h]->set_log(&logs[h]);
    }
    std::array<bool, 2> left = {true, true};
    for (std::size_t ids = std::max<std::size_t>(1, c.options.field_point_round); left[0] || left[1];
         ids = std::max(ids, std::min(2 * ids, kMostRoundIds))) {
        const std::size_t first = m.vertex_count();
        if (first + 2 * ids > mesh::kMaxVertices) break;  // the border's refinement goes on with the cap
        const std::vector<double> unset(3 * 2 * ids, 0.0);
        m.add_points(unset.data(), 2 * ids);
        for (std::size_t i = 0; i < 2 * ids; ++i) c.add_vertex(0);
        label.resize(first + 2 * ids, kNoHalf);
        std::array<FieldRefiner::HalfRound, 2> rounds;
        std::array<std::unique_ptr<mesh::SlotPool>, 2> pools;
        for (std::uint8_t h = 0; h < 2; ++h) {
            rounds[h].label = &label;
            rounds[h].half = h;
            rounds[h].next_id = static_cast<VertexId>(first + h * ids);
            rounds[h].end_id = static_cast<VertexId>(first + (h + 1) * ids);
            rounds[h].cap = h == 0 ? half_cap / 2 : half_cap - half_cap / 2;
            if (!left[h]) continue;
            pools[h] = std::make_unique<mesh::SlotPool>(m, FieldRefiner::kSlotMargin + kSlotsPerId * ids);
            rounds[h].pool = pools[h].get();
        }
        c.reserve_slots();
        mesh::run_chunks(2, c.options.threads > 1 ? 2 : 1, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t h = begin; h < end; ++h) {
                if (!left[h]) continue;
                const mesh::SlotPool::Use use(*pools[h]);
                left[h] = halves[h]->run_round(&rounds[h]);
            }
        });
        for (std::unique_ptr<mesh::SlotPool>& pool : pools) pool.reset();  // the slots left back to the free list
        for (std::unique_ptr<FieldRefiner>& half : halves) half->drop_stale();
        close_up_ids(c, label, halves, static_cast<VertexId>(first));
        if (half_stats[0].point_cap_hit || half_stats[1].point_cap_hit) break;
    }
    for (const RefineStats& h : half_stats) {
        stats.field_points += h.field_points;
        stats.size_fallbacks += h.size_fallbacks;
        stats.rejected += h.rejected;
        stats.cavity_tets += h.cavity_tets;
        stats.point_cap_hit = stats.point_cap_hit || h.point_cap_hit;
    }
    for (std::unique_ptr<FieldRefiner>& half : halves) {
        half->hand_over(border);
        half.reset();  // its scratch (per-slot marks) goes before the border's grows
    }
    const std::size_t before_border = stats.field_points;
    border.set_cap(cap);
    if (log) border.set_log(&logs[2]);
    border.run_queue();
    if (log) {
        log->border_before = border_before;
        log->in_half = {half_stats[0].field_points, half_stats[1].field_points};
        log->border_after = stats.field_points - before_border;
        for (std::vector<TetChange>& part : logs) log->insertions.insert(log->insertions.end(), part.begin(), part.end());
    }
}

}  // namespace

void insert_field_points(RefineContext& c, RefineStats& stats, const std::vector<TetId>* seeds, FieldPointsLog* log) {
    if (!seeds) return insert_in_halves(c, stats, log);
    FieldRefiner r(c, stats);
    const std::size_t before = stats.field_points;
    if (log) r.set_log(&log->insertions);
    r.queue_seeds(*seeds);
    r.run_queue();
    if (log) log->border_after = stats.field_points - before;
}

}  // namespace cbr::refine

#include "mesh/vertex_compaction.hpp"

namespace cbr::mesh {

void compact_vertices_from(TetMesh& m, std::size_t first, std::vector<VertexId>& keep_in_step,
                           std::vector<VertexId>* kept_old_ids) {
    const std::size_t n = m.vertex_count();
    if (kept_old_ids) kept_old_ids->clear();
    if (first >= n) return;
    constexpr VertexId kDropped = kGhostVertex;
    std::vector<VertexId> new_id(n - first, kDropped);
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m.vertex(t, i);
            if (v != kGhostVertex && v >= first) new_id[v - first] = 0;
        }
    }
    std::vector<double> kept;
    VertexId next = static_cast<VertexId>(first);
    for (std::size_t k = 0; k < new_id.size(); ++k) {
        if (new_id[k] == kDropped) continue;
        new_id[k] = next++;
        if (kept_old_ids) kept_old_ids->push_back(static_cast<VertexId>(first + k));
        const double* p = m.point(static_cast<VertexId>(first + k));
        kept.insert(kept.end(), p, p + 3);
    }
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m.vertex(t, i);
            if (v != kGhostVertex && v >= first) m.set_vertex(t, i, new_id[v - first]);
        }
    }
    m.truncate_vertices(first);
    if (!kept.empty()) m.add_points(kept.data(), kept.size() / 3);
    std::vector<VertexId> mapped;
    for (VertexId v : keep_in_step) {
        if (v < first) mapped.push_back(v);
        else if (new_id[v - first] != kDropped) mapped.push_back(new_id[v - first]);
    }
    keep_in_step.swap(mapped);
}

}  // namespace cbr::mesh

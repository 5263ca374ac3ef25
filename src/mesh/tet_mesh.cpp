#include "mesh/tet_mesh.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>

#include "mesh/slot_pool.hpp"

namespace cbr::mesh {

VertexId TetMesh::add_points(const double* xyz, std::size_t count) {
    assert(!journal_open_ && "points are not journaled");
    const std::size_t first = vertex_count();
    if (count > kMaxVertices - first) throw std::length_error("too many points");
    coords_.insert(coords_.end(), xyz, xyz + 3 * count);
    return static_cast<VertexId>(first);
}

void TetMesh::truncate_vertices(std::size_t count) {
    assert(!journal_open_ && "points are not journaled");
    if (count < vertex_count()) coords_.resize(3 * count);
}

void TetMesh::set_vertices(TetId t, VertexId a, VertexId b, VertexId c, VertexId d) {
    before_change(t);
    VertexId* v = tets_[t].v;
    v[0] = a;
    v[1] = b;
    v[2] = c;
    v[3] = d;
}

TetId TetMesh::allocate_tet() {
    if (slot_pools_ != 0)
        if (SlotPool* pool = SlotPool::in_use(*this)) return pool->take();
    if (!free_.empty()) {
        const TetId t = free_.back();
        before_change(t);
        free_.pop_back();
        if (journal_open_ && free_.size() < journal_.free_low) {
            journal_.free_low = free_.size();
            journal_.free_taken.push_back(t);
        }
        flags_[t] = 0;
        return t;
    }
    const std::size_t t = flags_.size();
    if (t >= kMaxTets) throw std::length_error("the mesh would exceed 2^30 tetrahedra");
    tets_.emplace_back();
    flags_.push_back(0);
    return static_cast<TetId>(t);
}

void TetMesh::release_tet(TetId t) {
    before_change(t);
    flags_[t] = kFlagFree;
    if (slot_pools_ != 0)
        if (SlotPool* pool = SlotPool::in_use(*this)) return pool->give(t);
    free_.push_back(t);
}

void TetMesh::reserve_tets(std::size_t count) {
    if (count > kMaxTets) count = kMaxTets;
    tets_.reserve(count);
    flags_.reserve(count);
}

void TetMesh::open_journal() {
    journal_open_ = true;
    Journal& j = journal_;
    if (++j.epoch == 0) {  // wrapped: no stamp may look current
        std::fill(j.stamp.begin(), j.stamp.end(), 0);
        j.epoch = 1;
    }
    j.slot_count = slot_count();
    if (j.stamp.size() < j.slot_count) j.stamp.resize(j.slot_count, 0);
    j.saved.clear();
    j.free_low = free_.size();
    j.free_taken.clear();
}

void TetMesh::undo_journal() {
    Journal& j = journal_;
    tets_.resize(j.slot_count);
    flags_.resize(j.slot_count);
    for (const SavedSlot& s : j.saved) {
        tets_[s.slot] = s.record;
        flags_[s.slot] = s.flags;
    }
    // The free list below free_low was never touched; above it, the
    // entries allocation took, put back in the order they stood.
    free_.resize(j.free_low);
    for (auto t = j.free_taken.rbegin(); t != j.free_taken.rend(); ++t) free_.push_back(*t);
    open_journal();
}

void TetMesh::close_journal() {
    journal_open_ = false;
    journal_.saved.clear();
    journal_.free_taken.clear();
}

void TetMesh::save_slot(TetId t) {
    journal_.stamp[t] = journal_.epoch;
    journal_.saved.push_back({tets_[t], t, flags_[t]});
}

void TetMesh::clear_tets() {
    assert(!journal_open_ && "clear_tets is not journaled");
    tets_.clear();
    flags_.clear();
    free_.clear();
}

void TetMesh::reorder_tets(const std::vector<TetId>& order) {
    assert(!journal_open_ && "reorder_tets is not journaled");
    assert(order.size() == live_count());
    std::vector<TetId> new_id(slot_count(), kNoTet);
    for (std::size_t i = 0; i < order.size(); ++i) new_id[order[i]] = static_cast<TetId>(i);
    LargeArray<TetRecord> tets(order.size());
    LargeArray<std::uint8_t> flags(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        TetRecord r = tets_[order[i]];
        for (FacetRef& n : r.n) n = make_facet(new_id[facet_tet(n)], facet_face(n));
        tets[i] = r;
        flags[i] = flags_[order[i]];
    }
    tets_.swap(tets);
    flags_.swap(flags);
    free_.clear();
}

}  // namespace cbr::mesh

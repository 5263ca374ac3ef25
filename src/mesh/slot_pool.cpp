#include "mesh/slot_pool.hpp"

#include <algorithm>
#include <stdexcept>

namespace cbr::mesh {
namespace {

thread_local SlotPool* pool_in_use = nullptr;

}  // namespace

SlotPool::SlotPool(TetMesh& m, std::size_t count) : m_(m) {
    if (m.journal_open()) throw std::logic_error("a slot pool is taken while the mesh's journal is open");
    const std::size_t listed = std::min(count, m.free_.size());
    if (count - listed > kMaxTets - m.slot_count()) throw std::length_error("the mesh would exceed 2^30 tetrahedra");
    // What may throw first (out of memory: new slots already appended stay
    // flagged free, leaked but not live), then the free list's slots.
    free_.reserve(count);
    const std::size_t first_new = m.slot_count();
    for (std::size_t k = listed; k < count; ++k) {
        m.tets_.emplace_back();
        m.flags_.push_back(kFlagFree);
    }
    for (std::size_t k = 0; k < listed; ++k) {
        free_.push_back(m.free_.back());
        m.free_.pop_back();
    }
    for (std::size_t t = first_new; t < m.slot_count(); ++t) free_.push_back(static_cast<TetId>(t));
    ++m.slot_pools_;
}

SlotPool::~SlotPool() {
    --m_.slot_pools_;
    try {
        m_.free_.insert(m_.free_.end(), free_.begin(), free_.end());
    } catch (...) {  // out of memory: the slots stay flagged free, leaked but not live (as surgery's releases)
    }
}

TetId SlotPool::take() {
    if (free_.empty()) throw std::logic_error("a thread's slot pool is empty");
    const TetId t = free_.back();
    free_.pop_back();
    m_.flags_[t] = 0;
    return t;
}

SlotPool* SlotPool::in_use(const TetMesh& m) { return pool_in_use && &pool_in_use->m_ == &m ? pool_in_use : nullptr; }

SlotPool::Use::Use(SlotPool& pool) : previous_(pool_in_use) { pool_in_use = &pool; }

SlotPool::Use::~Use() { pool_in_use = previous_; }

}  // namespace cbr::mesh

#include "mesh/slot_pool.hpp"

#include <stdexcept>

namespace cbr::mesh {
namespace {

thread_local SlotPool* pool_in_use = nullptr;

}  // namespace

SlotPool::SlotPool(TetMesh& m, std::size_t count) : m_(m) {
    if (m.journal_open()) throw std::logic_error("a slot pool is taken while the mesh's journal is open");
    free_.reserve(count);
    while (free_.size() < count && !m.free_.empty()) {
        free_.push_back(m.free_.back());
        m.free_.pop_back();
    }
    if (count - free_.size() > kMaxTets - m.slot_count())
        throw std::length_error("the mesh would exceed 2^30 tetrahedra");
    while (free_.size() < count) {
        free_.push_back(static_cast<TetId>(m.slot_count()));
        m.tets_.emplace_back();
        m.flags_.push_back(kFlagFree);
    }
}

SlotPool::~SlotPool() {
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

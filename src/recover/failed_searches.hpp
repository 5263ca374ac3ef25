// The nested edge-removal searches of flip recovery (remove_edge_deep)
// that failed in the mesh as it is now, with the budget each one spent.
//
// A search that fails without any flip succeeding leaves the mesh as it
// found it, and what it tries next depends only on the mesh: the same
// search (edge uv, same nesting depth) started again before any flip
// succeeds fails again and spends the same budget. Flip recovery meets
// such repeats all the time (a ring vertex's edge is tried from u, from v,
// and again from the next level up), so it asks here first and only pays
// the budget. The outcome, the budget left and so every later choice stay
// exactly what the full search would have given.
//
// Entries are stamped with the id of the mesh's state, which the caller
// sets on every change: a new id after a flip, the id the mesh had before
// when a rollback restores it. An entry of another state reads as unknown.
#pragma once

#include <array>
#include <cstdint>

#include "mesh/key_table.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::recover {

class FailedSearches {
public:
    static constexpr int kMaxDepth = 8;  // deeper searches are not remembered

    using State = std::uint64_t;

    void set_state(State s) { state_ = s; }

    // The budget a failed search of uv at `depth` spent in the current
    // mesh, or -1 when there is none.
    int spent(mesh::VertexId u, mesh::VertexId v, int depth) const {
        const Entry* e = failed_.find(key(u, v));
        if (e == nullptr || e->state != state_ || depth > kMaxDepth) return -1;
        return e->spent[static_cast<std::size_t>(depth)];
    }

    // Only for a search that ran to its end (not cut by the budget) and
    // changed nothing. The caller's states start at 1.
    void failed(mesh::VertexId u, mesh::VertexId v, int depth, int spent) {
        if (depth > kMaxDepth) return;
        Entry& e = failed_[key(u, v)];
        if (e.state != state_) {
            e.state = state_;
            e.spent.fill(-1);
        }
        e.spent[static_cast<std::size_t>(depth)] = spent;
    }

private:
    struct Entry {
        State state = 0;
        std::array<int, kMaxDepth + 1> spent{};
    };
    // The direction is kept: the search of vu tries the same removals in
    // another order, which would be the same only when all of them fail.
    static std::uint64_t key(mesh::VertexId u, mesh::VertexId v) { return (std::uint64_t{u} << 32) | v; }

    State state_ = 1;  // entries start at 0: unknown
    mesh::KeyTable<Entry> failed_;
};

}  // namespace cbr::recover

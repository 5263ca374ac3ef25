// Free tetrahedron slots set aside for one thread, so that threads that
// replace tetrahedra of disjoint parts of one mesh at the same time (the
// quality flips in two halves, refine/quality_flips.cpp) never share a
// slot or the mesh's free list, and the mesh's arrays do not grow under
// them. While a SlotPool::Use lives on a thread, TetMesh::allocate_tet and
// release_tet on that thread take from and give back to its pool instead
// of the mesh's free list; an empty pool throws (the caller checks size()
// before a replacement that may need slots).
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::mesh {

class SlotPool {
public:
    // Takes `count` free slots of m: the free list's last ones first, then
    // new slots at the end of the mesh (flagged free). Not while m's
    // journal is open (undo would not know the pool).
    SlotPool(TetMesh& m, std::size_t count);
    // Gives the slots left back to m's free list, in the pool's order
    // (without memory for that, they stay flagged free: leaked, not live).
    ~SlotPool();
    SlotPool(const SlotPool&) = delete;
    SlotPool& operator=(const SlotPool&) = delete;

    std::size_t size() const { return free_.size(); }
    // The slots the pool holds now (free in the mesh's flags).
    const std::vector<TetId>& slots() const { return free_; }

    // The pool of the calling thread for m, or nullptr.
    static SlotPool* in_use(const TetMesh& m);

    // Makes `pool` the calling thread's pool for its scope.
    class Use {
    public:
        explicit Use(SlotPool& pool);
        ~Use();
        Use(const Use&) = delete;
        Use& operator=(const Use&) = delete;

    private:
        SlotPool* previous_;
    };

private:
    friend class TetMesh;
    TetId take();
    void give(TetId t) { free_.push_back(t); }

    TetMesh& m_;
    std::vector<TetId> free_;
};

}  // namespace cbr::mesh

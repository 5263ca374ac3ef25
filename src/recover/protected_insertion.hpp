// Protected (constrained) Delaunay insertion of one point, with the cavity
// correction of §5.1 ("Algorithm: Cavity Correction"). Used by conforming
// recovery (Step 3: added points on missing edges and faces) and by the
// edge/face-added-point splittings (Steps 4-5: the mirror point inserted
// with "the half of Ball(e) on e*'s side" as the initial cavity).
//
// The cavity never contains a constraint face (TetMesh::is_constrained) or
// a face the caller forbids (`blocked`) in its interior, so no protected
// face is ever removed or split. The correction then shrinks (and, across
// faces coplanar with p, grows) the cavity until every boundary face is
// strictly visible from p, so the star of p is valid.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mesh/slot_marks.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::recover {

// True when face `face` of tetrahedron `tet` must not be crossed (e.g. the
// already-recovered parts of the face being recovered). Asked from either
// side of a face; it need not be symmetric.
using BlockedFace = std::function<bool(mesh::TetId tet, int face)>;

struct ProtectedInsertResult {
    bool ok = false;
    std::string why;                   // when !ok: readable reason
    std::vector<mesh::TetId> created;  // when ok: the star of p
    // When ok: the tetrahedra the star replaced (vertex ids), in the order
    // of the first slots of `created`, which they occupied:
    // replace_tets(m, created, cavity) undoes the insertion (slots of the
    // cavity as they were; the star's other slots freed).
    std::vector<std::array<mesh::VertexId, 4>> cavity;
    // Statistics of the §5.1 correction (also filled on failure).
    std::size_t initial_cavity = 0;  // tetrahedra before the correction
    std::size_t removed = 0;         // tetrahedra taken out
    std::size_t added = 0;           // tetrahedra taken in (coplanar faces)
};

// Inserts vertex p (coordinates already stored, in no tetrahedron yet).
// `start` is a live finite tetrahedron that contains p (closed). The
// cavity is the Bowyer-Watson one (insphere_sos; ghosts by the kernel's
// test), grown from `start` without crossing a protected face, then
// corrected (§5.1). On failure (p on a protected face, p equal to a vertex,
// `start` not containing p, replace_tets refusing) the mesh is unchanged
// bit for bit. (One-off insertions: the marks it allocates take time in
// proportion to the mesh; a loop of insertions holds a ProtectedInserter.)
ProtectedInsertResult insert_protected(mesh::TetMesh& m, mesh::VertexId p, mesh::TetId start,
                                       const BlockedFace& blocked = {});

// Same, with an explicit initial cavity (live tetrahedra; must contain
// `start` and no protected face between two of its members) instead of
// the grown one; then the §5.1 correction. `keep_seed`: the correction
// never drops a finite tetrahedron of `cavity` (where p does not see one of its
// faces it takes in the tetrahedron beyond, or fails) — for a point put
// on a crossing, which it must remove whole.
ProtectedInsertResult insert_protected_in_cavity(mesh::TetMesh& m, mesh::VertexId p, mesh::TetId start,
                                                 const std::vector<mesh::TetId>& cavity,
                                                 const BlockedFace& blocked = {}, bool keep_seed = false);

// The same two insertions, for callers that insert many points: the
// object keeps its scratch storage (per-slot marks, the cavity and star
// lists) from one insertion to the next instead of allocating it per call;
// the results are the same as the free functions'. The result returned
// refers to the object's storage and is valid until its next insertion.
class ProtectedInserter {
public:
    ProtectedInserter();
    ~ProtectedInserter();
    ProtectedInserter(const ProtectedInserter&) = delete;
    ProtectedInserter& operator=(const ProtectedInserter&) = delete;

    const ProtectedInsertResult& insert(mesh::TetMesh& m, mesh::VertexId p, mesh::TetId start,
                                        const BlockedFace& blocked = {});
    // The result of the last call (valid until the next one).
    const ProtectedInsertResult& last() const;
    // Undoes the last insertion, which succeeded, of point p (the mesh's
    // last vertex): its star goes back to the cavity it replaced and p
    // goes. `restored`: the tetrahedra put back. Returns whether each is
    // back in its own slot: true when the star had at least as many
    // tetrahedra (it took the cavity's slots first); of a larger cavity,
    // those beyond the star's count come back in other free slots. Throws
    // InternalError when the star is no longer in the mesh.
    bool undo_last(mesh::TetMesh& m, mesh::VertexId p, std::vector<mesh::TetId>& restored);
    const ProtectedInsertResult& insert_in_cavity(mesh::TetMesh& m, mesh::VertexId p, mesh::TetId start,
                                                  const std::vector<mesh::TetId>& cavity,
                                                  const BlockedFace& blocked = {}, bool keep_seed = false);

    // Whether every round of the correction sweeps the whole boundary and
    // checks that the cavity is in one piece (false, the default: only the
    // faces that can act, and the check only after a removal). The outcome
    // is the same, which the test that sets this proves.
    void set_full_rounds(bool full);

    // The per-slot marks each insertion starts a new round of, for a
    // caller to use between insertions (after SlotMarks::new_round): a
    // search that marks the tetrahedra of a point's cavity just before the
    // point is inserted (refine/field_points.cpp's probe) leaves their
    // words in cache for the insertion, where a mark array of its own
    // was a second cache miss per tetrahedron (on common3d-igea a third
    // of the insertions' samples were in reading and writing marks).
    mesh::SlotMarks& shared_marks();

    struct Scratch;  // protected_insertion.cpp

private:
    const ProtectedInsertResult& run(mesh::TetMesh& m, mesh::VertexId p, mesh::TetId start,
                                     const BlockedFace& blocked, const std::vector<mesh::TetId>* seed,
                                     bool keep_seed);

    std::unique_ptr<Scratch> scratch_;
};

}  // namespace cbr::recover

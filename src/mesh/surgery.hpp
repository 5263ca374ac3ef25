// Mesh surgery: replace a set of tetrahedra by another set that tiles the
// same region. The one mechanism behind every local change of the mesh:
// the flips of §5.1 (Definition 5.6 Swap23/32/44, Definition 5.8 shell
// transformation), the cap and ball transformations, Steiner point
// insertion and suppression.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "mesh/ball_shell.hpp"
#include "mesh/slot_marks.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::mesh {

// Why replace_tets refused; the checks run in this order and the first one
// that fails is reported.
enum class ReplaceResult {
    kDone,
    // An old id that is not a live tetrahedron or is listed twice; empty
    // `old` or `fresh`; a fresh tetrahedron with a vertex id out of range or
    // a repeated vertex.
    kBadInput,
    // `fresh` does not tile the region of `old`: its unshared faces are not
    // exactly the boundary faces of `old` (as vertex sets, same orientation),
    // or a face is shared by more than two fresh tetrahedra or by two with
    // the same orientation.
    kNotTiling,
    // A constraint face interior to `old` would not be a face of `fresh`.
    kRemovesConstraint,
    // A finite fresh tetrahedron is not positively oriented (exact).
    kInverted,
    // A fresh ghost would leave the hull non-convex (or a ghost's hull face
    // would border another ghost).
    kNotConvex,
};

const char* to_string(ReplaceResult r);

// Replaces the tetrahedra `old` (live; normally a connected region) by
// `fresh` (4 vertex ids each; kGhostVertex allowed once per tetrahedron, in
// any position: it is moved to position 3 by an even permutation). On
// kDone: the slots of `old` are reused in order, then new slots taken;
// surplus old slots are freed; every neighbour link is set, the outside
// neighbours' back links included; constraint marks are kept: boundary
// faces carry the mark they had in `old` (outside neighbours keep theirs)
// and a constraint face interior to `old` stays marked on both sides.
// `created` (optional) receives the fresh tetrahedra's ids in the order of
// `fresh`; scratch marks (kFlagMarkA/B) of the fresh tetrahedra are clear.
//
// Checks, all exact (see ReplaceResult): face matching by sorted vertex
// triples with orientation parity (O(k log k) for k faces); orient3d > 0
// for finite fresh tetrahedra; for every fresh ghost (a, b, c, oo), the
// hull stays locally convex: orient3d(a, b, c, x) <= 0 for every finite
// vertex x of `old`, and for the far vertex x of each neighbouring hull
// face (across its three hull edges, fresh or outside: this catches a new
// vertex outside the hull that would see more than the faces replaced);
// and its hull face borders a finite tetrahedron.
//
// On any result but kDone the mesh is unchanged. Exceptions: std::bad_alloc
// from the checks leaves the mesh unchanged; from the slot allocation, the
// slots taken so far are given back (flagged free).
ReplaceResult replace_tets(TetMesh& m, const std::vector<TetId>& old,
                           const std::vector<std::array<VertexId, 4>>& fresh,
                           std::vector<TetId>* created = nullptr);

// replace_tets for the star of a new point: replaces `old` by the cone from
// vertex p (in no tetrahedron yet) over the boundary faces of `old`, listed
// by tetrahedron of `old` in the order given, then by face. Each cone is
// the tetrahedron with p in place of the vertex opposite its face. Same
// result, checks, effects and `created` as replace_tets(m, old, fresh) with
// that list as `fresh`; only cheaper, for callers that insert many points:
// the face matching follows the cone's structure (a boundary face is the
// face of one cone; a face through p is shared by the two cones of a
// boundary edge) instead of sorting every face, and the scratch storage is
// kept from one call to the next.
class ConeReplacer {
public:
    ConeReplacer();
    ~ConeReplacer();
    ConeReplacer(const ConeReplacer&) = delete;
    ConeReplacer& operator=(const ConeReplacer&) = delete;

    ReplaceResult replace(TetMesh& m, const std::vector<TetId>& old, VertexId p,
                          std::vector<TetId>* created = nullptr);

    // Undoes the last replace() that returned kDone, given the `created`
    // it returned: the same as replace_tets(m, created, the old
    // tetrahedra as they were, restored), only without its checks and
    // sorting (where points are tried, an undone insertion is as common as
    // a kept one: the unblocking points of flip recovery, sliver points).
    // The mesh must not have changed since replace(): the star's
    // tetrahedra are checked to be live with p where it was put, and false
    // is returned, the mesh unchanged, when they are not, or when there is
    // nothing to undo (once undone, or after a replace() that failed).
    bool restore_last(TetMesh& m, const std::vector<TetId>& created, std::vector<TetId>* restored = nullptr);

    // replace() marks the old tetrahedra in `marks` (a new round each
    // call) instead of in marks of its own; nullptr: its own again. For
    // an owner that has just marked the same tetrahedra in `marks` (a
    // point insertion's cavity, recover/protected_insertion.cpp): their
    // words are then in cache.
    void share_marks(SlotMarks* marks);

    struct Scratch;  // surgery.cpp

private:
    void remember_old(const TetMesh& m, const std::vector<TetId>& old, VertexId p);

    std::unique_ptr<Scratch> scratch_;
};

// replace_tets for the 2-3 flip (Definition 5.6 Swap23): replaces
// tetrahedron t = (face f, apex d) and its neighbour n across face f
// (apex e) by (a, b, e, d), (b, c, e, d), (c, a, e, d), where a, b, c is
// face f as kFaceVertices[f] lists it in t. Same result, checks, effects
// and `created` as replace_tets(m, {t, n}, those three), only cheaper
// (flip recovery and the quality flips try it hundreds of thousands of
// times): the nine faces are linked by the flip's structure instead of by
// sorting, and the scratch storage is kept from one call to the next. A
// flip that involves the ghost vertex takes replace_tets' own path.
class TwoThreeReplacer {
public:
    TwoThreeReplacer();
    ~TwoThreeReplacer();
    TwoThreeReplacer(const TwoThreeReplacer&) = delete;
    TwoThreeReplacer& operator=(const TwoThreeReplacer&) = delete;

    ReplaceResult replace(TetMesh& m, TetId t, int f, std::vector<TetId>* created = nullptr);

    struct Scratch;  // surgery.cpp

private:
    std::unique_ptr<Scratch> scratch_;
};

// A triangle of the ring polygon of a shell: three indices into Shell::ring
// in cyclic ring order (each a rotation of i < j < k).
using RingTriangle = std::array<int, 3>;

// What the caller of ShellReplacer has checked of the fresh tetrahedra.
enum class ShellGeometry {
    // Nothing: every geometric check of replace_tets runs.
    kUnchecked,
    // best_ring_triangulation chose the triangles: every finite fresh
    // tetrahedron is positively oriented (exact) and every fresh ghost has
    // the shell's finite vertices on the inner side of (or on) its hull
    // face. Those checks are skipped; the rest of the convexity rule (the
    // hull faces next to a fresh ghost outside the shell) still runs.
    kScoredRing,
};

// replace_tets for the shell transformation (Definition 5.8): replaces the
// shell of uv by the ring triangles coned to v and (reversed) to u: for
// each triangle (i, j, k), in the order given, (ri, rj, rk, v) then
// (ri, rk, rj, u). `shell` must be the current shell of uv (from shell())
// in a valid mesh. Same result, checks, effects and `created` as
// replace_tets(m, shell.tets, that list), only cheaper (edge removal runs
// millions of times in flip recovery): the faces are matched by the
// shell's structure (a ring edge's new faces meet the old faces opposite u
// and v of its shell tetrahedron; a chord's are shared by the two
// triangles on it) instead of by sorting, the scratch storage is kept from
// one call to the next, and the checks `geometry` vouches for are skipped.
class ShellReplacer {
public:
    ShellReplacer();
    ~ShellReplacer();
    ShellReplacer(const ShellReplacer&) = delete;
    ShellReplacer& operator=(const ShellReplacer&) = delete;

    ReplaceResult replace(TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                          const std::vector<RingTriangle>& triangles, ShellGeometry geometry,
                          std::vector<TetId>* created = nullptr);

    struct Scratch;  // surgery.cpp

private:
    std::unique_ptr<Scratch> scratch_;
};

}  // namespace cbr::mesh

// Flips (§5.1, Definition 5.6: Swap23, Swap32, Swap44) and edge removal
// (Definition 5.8, the shell transformation; Shewchuk's edge removal), all
// through replace_tets (flip32, flip44 and remove_edge through its
// specialisation to shells, ShellReplacer: same checks and result): a flip
// is done only when every new tetrahedron is positively oriented (exact),
// no constraint face is removed (replace_tets refuses) and no protected
// edge disappears (the caller's callback).
//
// Ghosts: kGhostVertex is treated as any other apex or ring vertex; the
// convexity rule of replace_tets accepts a flip touching the hull only when
// the hull stays convex (e.g. the 2-2 flip of a flat hull quadrilateral,
// which is a 4-4 flip with two ghosts).
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <vector>

#include "mesh/ball_shell.hpp"
#include "mesh/surgery.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::mesh {

enum class FlipResult {
    kDone,
    kNotApplicable,        // not the configuration of this flip (shell size, no coplanar diagonal, bad ids)
    kProtectedEdge,        // the edge that would disappear is protected
    kNoValidTriangulation, // edge removal: every ring triangulation has an inverted tetrahedron
    kRemovesConstraint,    // replace_tets: a constraint face would disappear
    kInverted,             // replace_tets: a new tetrahedron is not positively oriented
    kNotConvex,            // replace_tets: the hull would not stay convex
};

const char* to_string(FlipResult r);

// Called with the endpoints of an edge that a flip would remove (either
// order; one may be kGhostVertex); true forbids the flip. Empty: nothing
// is protected.
using EdgeProtect = std::function<bool(VertexId, VertexId)>;

// Swap23 on face f of t: t = (a, b, c, d) with face abc, its neighbour
// (a, b, c, e) → deab, debc, deca (valid when de crosses the interior of
// abc). No edge disappears: `protect` is accepted for a uniform signature
// and never called. `created`: the three new tetrahedra.
FlipResult flip23(TetMesh& m, TetId t, int f, const EdgeProtect& protect = {},
                  std::vector<TetId>* created = nullptr);

// Swap32 on edge uv (t contains it) whose shell has exactly three
// tetrahedra, with ring r0 r1 r2 → r0 r1 r2 v and r0 r2 r1 u (valid when uv
// crosses the interior of r0 r1 r2).
FlipResult flip32(TetMesh& m, TetId t, VertexId u, VertexId v, const EdgeProtect& protect = {},
                  std::vector<TetId>* created = nullptr);

// Swap44 on edge uv whose shell has four tetrahedra, with ring r0 r1 r2 r3
// where u, v, ri, ri+2 are coplanar: the planar quadrilateral u ri v ri+2
// swaps its diagonal uv for ri ri+2 (the four tetrahedra around ri ri+2).
// kNotApplicable when neither pair of opposite ring vertices is coplanar
// with uv (remove_edge handles the general shell of four).
FlipResult flip44(TetMesh& m, TetId t, VertexId u, VertexId v, const EdgeProtect& protect = {},
                  std::vector<TetId>* created = nullptr);

// Edge removal is not tried on shells larger than this: the search is
// O(n^3), and large shells (the fans of CAD caps) are never removable in
// practice. Measured in flip recovery on the shared surfaces: of 6,433
// shells of 17-32 tetrahedra 13 could be removed, of 154 shells of
// 129-256 (thingicsg-sprocket) none, and those took 93% of its recovery's
// instructions.
inline constexpr std::size_t kMaxRemovalShell = 64;

// Edge removal: the shell of uv (n >= 3 tetrahedra, ring r0..r(n-1)) is
// replaced by 2(n-2) tetrahedra: a triangulation of the ring polygon
// coned to u and to v, the one that maximizes the minimum tet_quality
// (dynamic programming over the polygon, O(n^3)). A ghost in the ring or
// as an endpoint is allowed; ghost tetrahedra then count as quality +inf
// when they satisfy the convexity rule against the shell's vertices, -inf
// otherwise. kNoValidTriangulation when no triangulation has every
// tetrahedron valid; kNotApplicable for a shell of more than
// kMaxRemovalShell tetrahedra.
FlipResult remove_edge(TetMesh& m, TetId t, VertexId u, VertexId v, const EdgeProtect& protect = {},
                       std::vector<TetId>* created = nullptr);
// The same with the shell of uv already found: `shell` must be the current
// shell of uv (from shell()). For callers that need the shell again when
// the removal fails (any result but kDone leaves the mesh, and so the
// shell, unchanged), instead of walking it twice.
FlipResult remove_edge(TetMesh& m, VertexId u, VertexId v, const Shell& shell, const EdgeProtect& protect = {},
                       std::vector<TetId>* created = nullptr);

// The shell transformation (Definition 5.8) with a given triangulation of
// the ring: every triangle (ri, rj, rk) gives (ri, rj, rk, v) and (ri, rk,
// rj, u). `shell` must be the current shell of uv (from shell()). Does not
// consult a protection callback. kNotApplicable when the triangles do not
// triangulate the ring polygon.
FlipResult transform_shell(TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                           const std::vector<RingTriangle>& triangles, std::vector<TetId>* created = nullptr);

// The positions of the shell's ring in the order in which a search that
// removes an edge from u or v to a ring vertex first (flip recovery's
// nested edge removals) should try them: first the vertices where the
// ring is not convex as seen from u and v, whose ear (r[i-1], r[i],
// r[i+1]) cones a tetrahedron that is not positively oriented (exact; a
// ghost counts as remove_edge counts it), then the others, each group in
// ring order. No valid triangulation of the ring has such an ear, so
// each of them narrows the triangulations left; when none is left, taking
// one of them out of the ring (removing the edge from u or v to it) is
// the likeliest way to make one. Returns the number of blocking positions
// (they are order[0 .. count)).
std::size_t ring_positions_blocking_first(const TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                                          std::vector<std::size_t>& order);

// Whether a ring whose valid ears are order[blocking ..] (as
// ring_positions_blocking_first leaves them) may have a valid
// triangulation: a triangulation of a polygon of four or more vertices has
// two ears at vertices that are not neighbours (ears at neighbouring
// vertices cut off diagonals that cross), and each of its triangles must
// be valid. A necessary condition only; on the feeder body's flip
// recovery 92% of the rings without a valid triangulation fail it.
bool ring_may_be_triangulated(const std::vector<std::size_t>& order, std::size_t blocking);

// Shape quality of tetrahedron abcd: 72 sqrt(3) V / (sum of squared edge
// lengths)^(3/2), 1 for the regular tetrahedron, in (0, 1] when
// orient3d(a, b, c, d) > 0 (exact), -infinity otherwise.
double tet_quality(const double* a, const double* b, const double* c, const double* d);

// What best_ring_triangulation maximizes: the minimum of `measure` over the
// finite tetrahedra a triangulation cones (a measure is -infinity for a
// tetrahedron that is not positively oriented, exact, and above it for
// every other: a ring with one valid triangulation gets it without its
// measure when nothing else is asked), counting only
// triangulations whose minimum is strictly above `floor`. A caller that
// will refuse anything not above a bar gives it as the floor: every
// sub-polygon whose best falls to it is dropped at once, so a ring that
// cannot beat the bar costs a fraction of the full search.
// With `chord_allowed`, only triangulations whose every chord (a new
// edge between two ring vertices that are not neighbours) it allows.
struct RingObjective {
    double (*measure)(const double*, const double*, const double*, const double*) = tet_quality;
    double floor = -std::numeric_limits<double>::infinity();
    std::function<bool(VertexId, VertexId)> chord_allowed;
};

// The triangulation of the ring that remove_edge would use (empty when
// none is valid), and its minimum quality. Every finite tetrahedron it
// cones, (ri, rj, rk, v) and (ri, rk, rj, u) for a triangle (i, j, k), is
// positively oriented (exact orient3d), and every ghost keeps the shell's
// finite vertices on the inner side of its hull face.
std::vector<RingTriangle> best_ring_triangulation(const TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                                                  double* min_quality = nullptr);
// The same into `triangles` (its storage reused); false when none is valid.
bool best_ring_triangulation(const TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                             std::vector<RingTriangle>& triangles, double* min_quality = nullptr);
// The triangulation that maximizes `objective` (false when none is above
// its floor), and its minimum measure.
bool best_ring_triangulation(const TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                             std::vector<RingTriangle>& triangles, double* min_quality,
                             const RingObjective& objective);

}  // namespace cbr::mesh

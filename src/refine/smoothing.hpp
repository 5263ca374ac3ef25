// Smoothing of interior vertices (Du & Wang 2004, §6: the remaining Steiner
// points "repositioned ... by mesh smoothing", and step (e), the final
// optimisation). Only vertices that are not input points move (field
// points and recovery's Steiner points), only inside the bounded regions,
// and a move is kept only when every tetrahedron of the vertex's ball stays
// positively oriented (exact orient3d: the vertex stays strictly inside its
// ball, so it never reaches the surface), no edge of the vertex leaves the
// size bound (one already over it may stay over, no longer than it was),
// and the ball gets better: its smallest radius ratio grows when it has a
// bad tetrahedron (below 0.15), else its mean grows while its smallest
// stays at least min(old smallest, 0.3) (smoothing.cpp). Otherwise the
// vertex goes back, bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "refine/refine_context.hpp"
#include "refine/tet_measures.hpp"

namespace cbr::refine {

// One sweep over the movable vertices whose ball changed since the previous
// pass (RefineContext::changed); returns the number of moves kept. The
// inner vertices of two halves of the mesh first, the halves on two
// threads when c.options.threads > 1, then the vertices between them
// (vertex_halves.hpp): the same moves with any number of threads.
std::size_t smooth_vertices(RefineContext& c);

// After the optimisation passes, for Table II's minimum dihedral angle:
// each movable vertex whose ball has a tetrahedron with a dihedral angle
// below `below_degrees` moves to where the ball's smallest dihedral angle
// is larger, as long as the ball keeps its radius ratios (no more
// tetrahedra under `keep_radius_ratio`, 90% of the mean; the worst of
// those under it may fall); the same validity and size rules as above.
// Only balls with a tetrahedron created or reshaped in pass `since` or
// after it (RefineContext::changed_since) are tried: the others failed in
// an earlier call and would fail again. Returns the number of moves;
// `log`, for tests, gets each move in order.
struct VertexMove {
    mesh::VertexId v;
    Point from, to;
};
std::size_t smooth_for_dihedrals(RefineContext& c, double below_degrees, double keep_radius_ratio,
                                 std::vector<VertexMove>* log = nullptr, std::uint32_t since = 0);

}  // namespace cbr::refine

// Steiner point suppression retried after refinement (Du & Wang 2004, §6:
// "Steiner points minimization", and Table II's last row, "bad elements
// connecting SP", 0 in every example). Recovery tries to suppress every
// Steiner point once, in the bare boundary mesh, where many cannot go (no
// tetrahedralization of their ball without them). After the field points,
// flips and smoothing, the ball of a Steiner point is another polyhedron,
// and the same retetrahedralization (recover::suppress_vertex: contraction
// onto a link vertex, or flipping the ball down to four tetrahedra) often
// succeeds. Where it still fails, the field points of the point's link are
// suppressed first (each one merges its ball into the point's, changing
// the polyhedron) and the point is tried again.
//
// Only Steiner points of the bounded regions whose ball has a tetrahedron
// below the threshold are tried (a good one stays: §6 wants them well
// placed, not necessarily gone), and a suppression is kept only when its
// new tetrahedra have no more below the threshold than the ball had (the
// bad elements must not merely move elsewhere). Then the field points come
// back where the suppressions left tetrahedra over the size bound or the
// quality bound (field_points.hpp, on the new tetrahedra and one ring of
// vertices around them and around the Steiner points left).
//
// Suppression changes only the ball's region (its new tetrahedra get the
// ball's region), removes no constraint face and keeps every tetrahedron
// positively oriented (exact; recover/steiner_suppression.hpp). A
// suppressed point (Steiner or field) is in no tetrahedron any more: the
// caller compacts the vertex ids (mesh/vertex_compaction.hpp) before the
// mesh is checked or returned.
#pragma once

#include <cstddef>
#include <vector>

#include "refine/refine_context.hpp"
#include "refine/refine_options.hpp"

namespace cbr::refine {

// Tries each point of `steiner` whose ball has a tetrahedron with radius
// ratio below `threshold`; the suppressed ones are erased from `steiner`
// (the others keep their order), counted in stats.steiner_suppressed, and
// the field points removed on the way are taken off stats.field_points
// (those inserted again are counted as usual). Sets `dropped` when a
// vertex left the mesh. Returns the number of Steiner points suppressed.
std::size_t remove_bad_steiner_points(RefineContext& c, std::vector<mesh::VertexId>& steiner, double threshold,
                                      RefineStats& stats, bool& dropped);

// The tetrahedra of the bounded regions with radius ratio below
// `threshold` and a corner in `steiner` (Table II's last row).
std::size_t bad_tets_at_steiner(const RefineContext& c, const std::vector<mesh::VertexId>& steiner,
                                double threshold);

}  // namespace cbr::refine

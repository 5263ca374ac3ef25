// Relocation of recovery's remaining Steiner points whose tetrahedra stay
// bad after refinement (Du & Wang 2004, §6: the remaining Steiner points
// are "repositioned ... to better locations", and Table II's last row, "bad
// elements connecting SP", is 0 in every example).
//
// Smoothing (smoothing.hpp) moves a vertex only within its ball, keeping
// its tetrahedra: a Steiner point that recovery left a hair above a few
// input triangles (a flat tetrahedron on each) often cannot leave that
// spot, because other faces of its link pass just as close to it and fence
// it in. Here the point moves together with a retetrahedralization of its
// neighbourhood: the cavity is its ball, then the ball and the tetrahedra
// next to it, one ring after another (never across a constraint face,
// always in the ball's region), and the point goes to the best of a few
// candidates from which every boundary face of the cavity is strictly
// visible (exact orient3d). The cavity is then replaced by the star of the
// point over its boundary, the point keeping its vertex id: moving within
// the ball is the cavity of ring 0.
//
// Guarantees: no input point moves; the star is valid (each boundary face
// sees the point strictly, replace_tets checks it again exactly), so the
// point is strictly inside the cavity's region and never on the surface
// (every input triangle is a face of the mesh, and no face of the mesh
// meets the interior of a cavity that crosses none); no constraint face is
// removed; no other vertex leaves the mesh (a cavity that would swallow
// one is not used); every new edge keeps the size bound. A relocation is
// kept only when its star is no worse than the cavity (worst radius ratio
// no lower, no more tetrahedra below the threshold) and has fewer of them
// at Steiner points than the cavity had (or as many and a higher worst):
// every tetrahedron of the star has the point as a corner, so the bad
// elements must not come back at it. Among the candidates and cavities,
// the largest such gain wins, then the highest worst; the search stops at
// the smallest cavity that leaves the point no bad tetrahedron.
#pragma once

#include <cstddef>
#include <vector>

#include "refine/refine_context.hpp"

namespace cbr::refine {

// Tries every Steiner point of `steiner` (in the bounded regions) whose
// ball has a tetrahedron with radius ratio below `threshold`; returns the
// number of points relocated. Vertex ids do not change.
std::size_t relocate_steiner_points(RefineContext& c, const std::vector<mesh::VertexId>& steiner, double threshold);

}  // namespace cbr::refine

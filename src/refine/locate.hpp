// Point location for refinement: a visibility walk from a tetrahedron of a
// bounded region toward a point, that never crosses a constraint face nor
// leaves the region (§6: field points are inserted inside the domain only;
// a point the walk cannot reach without crossing the surface lies outside
// the start's region, or behind a part of the surface).
#pragma once

#include "mesh/tet_mesh.hpp"
#include "refine/refine_context.hpp"
#include "refine/vertex_halves.hpp"

namespace cbr::refine {

enum class Located {
    kInside,   // strictly inside `tet` (all four orient3d > 0): on no face
    kOnFace,   // in the closed `tet`, on one or more of its faces, none of them a constraint face
    kBlocked,  // the walk would cross a constraint face, a region border or the hull
    kOnSurface,  // on a constraint face of `tet` (exact)
    kLost,     // step limit reached (a cycle in a non-Delaunay mesh)
    kForeign,  // the walk would enter a tetrahedron that is not the claim's (`tet`: the last one that is)
};

struct Location {
    Located where = Located::kLost;
    mesh::TetId tet = mesh::kNoTet;
};

// With `claim`, start is the claim's and the walk never enters a
// tetrahedron that is not (kForeign): it reads only the claim's
// tetrahedra and the corners of their neighbours.
Location locate_in_region(const RefineContext& c, mesh::TetId start, const double* p,
                          const HalfClaim* claim = nullptr);

}  // namespace cbr::refine

// Point location for refinement: a visibility walk from a tetrahedron of a
// bounded region toward a point, that never crosses a constraint face nor
// leaves the region (§6: field points are inserted inside the domain only;
// a point the walk cannot reach without crossing the surface lies outside
// the start's region, or behind a part of the surface).
#pragma once

#include "mesh/tet_mesh.hpp"
#include "refine/refine_context.hpp"

namespace cbr::refine {

enum class Located {
    kInside,   // strictly inside `tet` (all four orient3d > 0): on no face
    kOnFace,   // in the closed `tet`, on one or more of its faces, none of them a constraint face
    kBlocked,  // the walk would cross a constraint face, a region border or the hull
    kOnSurface,  // on a constraint face of `tet` (exact)
    kLost,     // step limit reached (a cycle in a non-Delaunay mesh)
};

struct Location {
    Located where = Located::kLost;
    mesh::TetId tet = mesh::kNoTet;
};

Location locate_in_region(const RefineContext& c, mesh::TetId start, const double* p);

}  // namespace cbr::refine

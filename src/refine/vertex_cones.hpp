// Cone retetrahedralization, the last step of refinement and a step of its
// extra passes for Steiner points (refine.cpp): a cavity is replaced by
// the cone from one of its own vertices over its boundary. No point is
// added or moved; only the connectivity changes, as with a flip (a 2-3
// flip is the cone from one apex over the two tetrahedra, a 3-2 flip the
// cone from a ring vertex over the three), but the cavity is not bounded
// to a shell or a face pair: it grows from the tetrahedron to be removed
// towards the apex until the apex sees all of it.
//
// Used for two kinds of tetrahedra the earlier steps leave: those with a
// dihedral angle below a bound (Table II's minimum), and those below the
// radius-ratio threshold with a Steiner corner (Table II's last row, "bad
// elements connecting SP", which §6 wants at 0). Where a Steiner point
// sits in a layer of the domain thinner than its triangles, a vertex on
// the other side of its flat tetrahedra may take them over as a cone's
// apex; and a cavity around the point's whole ball may have a cone
// without the point, which then leaves the mesh (§6, "Steiner points
// minimization", where the contractions of recover::suppress_vertex,
// cones over the ball alone from a link vertex, found no way).
//
// For a tetrahedron t and an apex u (a vertex of the tetrahedra around
// t's corners): the cavity starts as {t}, or as the ball of a Steiner
// corner s of t (all of it in t's region); each boundary face of it that
// does not contain u and that u does not see strictly (exact orient3d)
// takes the tetrahedron behind it in, never across a constraint face,
// never out of t's region, while the cavity has fewer than kMaxCavity
// tetrahedra. When every such face sees u, and no vertex but u (and s) is
// inside the cavity (the cone would drop it from the mesh), the cone from
// u over those faces is valid: each of its tetrahedra is positively
// oriented, and they tile the cavity (a ray from u into the cavity leaves
// it through exactly one boundary face, every crossing being outwards);
// replace_tets checks both again exactly. No constraint face is removed
// (none is inside the cavity), every new tetrahedron takes t's region, no
// point lies on the surface that did not before, and only s may leave.
//
// A cone is kept when its tetrahedra are no worse where Table II counts:
// no more of them under the threshold than the cavity had, no more of
// those at a Steiner point, none under both the threshold and the
// cavity's worst radius ratio, every new edge within the size bound or
// no longer than an edge of the cavity over it (as a flip for the
// smallest angle: refine_options.hpp, kEdgeFactor); and better where t
// was picked for: fewer bad tetrahedra at a Steiner point, or a smallest
// dihedral angle above the cavity's by kAngleGain. Among the apexes, the
// largest drop in bad tetrahedra at Steiner points wins, then the largest
// smallest angle.
#pragma once

#include <cstddef>
#include <vector>

#include "refine/refine_context.hpp"
#include "refine/refine_options.hpp"

namespace cbr::refine {

// One sweep over the tetrahedra of the bounded regions with a dihedral
// angle below `below_degrees`, or with radius ratio below `threshold` and
// a corner in `steiner`; each gets the best cone, if any is kept. Returns
// the number of cones made, also added to stats.vertex_cones. The Steiner
// points the cones took out of the mesh are erased from `steiner` (the
// others keep their order) and counted in stats.steiner_suppressed, and
// then `dropped` is set: they are in no tetrahedron, and the caller
// compacts the vertex ids (mesh/vertex_compaction.hpp). `log`, for tests,
// gets each cone's replaced and made tetrahedra.
std::size_t improve_by_vertex_cones(RefineContext& c, std::vector<mesh::VertexId>& steiner, double below_degrees,
                                    double threshold, RefineStats& stats, bool& dropped,
                                    std::vector<TetChange>* log = nullptr);

}  // namespace cbr::refine

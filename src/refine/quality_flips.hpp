// Quality-improving flips of the interior (Du & Wang 2004, §6 step (e):
// "optimize the mesh with local ... topological operations"): 2-3 flips
// and edge removals (3-2, 4-4 and larger shells, mesh/flips.hpp), each done
// only when the smallest radius ratio of the tetrahedra it replaces grows
// (improve_by_flips), or their smallest dihedral angle
// (improve_dihedrals_by_flips). An edge removal takes the ring
// triangulation with the best smallest value of that measure among those
// whose chords keep the size bound (mesh::RingObjective).
// A constraint face is never removed (no face through a surface edge is
// touched; replace_tets refuses it anyway), the exterior is not changed,
// and no new edge breaks the size bound.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "refine/refine_context.hpp"

namespace cbr::refine {

// One sweep over the tetrahedra of the bounded regions whose radius ratio
// is below `threshold` and that changed, or have a face neighbour that
// changed, since the previous pass (RefineContext::changed_near); returns
// the number of flips done. The sweep runs in two halves of the mesh, at
// once with c.options.threads > 1, then over their border (the mesh is the
// same with any number of threads; quality_flips.cpp). For tests, `log`
// gets each flip (the two halves' in turn, then the border's).
struct HalvesFlips {
    std::array<std::size_t, 2> in_half = {0, 0};  // flips among the tetrahedra of each half
    std::size_t on_border = 0;                     // flips of the sweep after them
    std::size_t total() const { return in_half[0] + in_half[1] + on_border; }
};
HalvesFlips improve_by_flips(RefineContext& c, double threshold, std::vector<TetChange>* log = nullptr);

// The same flips judged by the smallest dihedral angle instead (Table II's
// minimum dihedral angle, which the radius ratio does not always follow):
// sweeps over the tetrahedra with a dihedral angle below `below_degrees`,
// the first over all of them (with `since` > 0: over those that changed,
// or have a face neighbour that changed, in pass `since` or after it), the
// next over those near the last sweep's flips, at most `max_sweeps`;
// returns the number of flips done and the pass of the last sweep. Each
// flip raises the smallest angle among the tetrahedra it replaces, so
// the mesh's smallest angle never falls; and it makes no tetrahedron whose
// radius ratio is below both `keep_radius_ratio` and the worst of those
// it replaces (the angle and the radius ratio can move apart). With
// options.edge_removal_after_another, an edge removal that no
// triangulation of the edge's ring allows may follow the removal of an
// edge from one of its ends to a ring vertex (the pair judged as one flip:
// what it leaves against all it replaced). With
// options.dihedral_chords_up_to_removed_edge, a flip that removes an edge
// over the size bound may make new edges over it too, none longer than
// that edge.
struct DihedralFlips {
    std::size_t flips = 0;          // flips done, each removal of a pair counted
    std::size_t after_another = 0;  // of them, pairs of edge removals
    // The pass of the last sweep (RefineContext::pass): what changed in it
    // or after it is what a later call needs to look at (its `since`).
    std::uint32_t last_sweep = 0;
};
// `log`, for tests, gets each flip (a pair as one).
DihedralFlips improve_dihedrals_by_flips(RefineContext& c, double below_degrees, double keep_radius_ratio,
                                         int max_sweeps, std::vector<TetChange>* log = nullptr,
                                         std::uint32_t since = 0);

}  // namespace cbr::refine

// Removal of slivers that Delaunay refinement cannot reach (Du & Wang
// 2004, §6 step (e), "optimisation"). A sliver whose circumcentre is
// refused (outside its region, or too close to the surface) and whose
// circumradius is small stays after refinement; two kinds dominate the
// worst elements of the shared surfaces: a flat tetrahedron spanning two
// nearly coplanar input triangles that share an edge (four surface
// vertices), and flat tetrahedra among field points crowded near a sharp
// feature. Flips and smoothing do not always remove them, and no
// Delaunay insertion can without a point nearly on the surface (the
// sliver's circumball barely reaches into the domain).
//
// Here a point goes in with a chosen cavity instead (the protected
// insertion kernel, recover::insert_protected_in_cavity). First the shell
// of each of the sliver's interior edges (a flat tetrahedron has two edges
// with dihedral angles near 180 degrees; against a ridge of two nearly
// coplanar input triangles the shell of the edge under the ridge is the
// only small cavity with room for a well-shaped star): there the best
// candidate is climbed by a pattern search and counts only when its star
// has no sliver left. Else the sliver and its neighbours across
// non-constraint faces, one ring after another up to four, all in one
// region (the smallest that admits a valid star, beating the cavity's
// worst tetrahedron by kSliverGain). When no ring has one and the
// sliver's corners are four input points (nothing can move them), a
// shell's best star is taken after all if it lifts the shell's worst by
// kSliverGain and to a tenth of the threshold, though it keeps a sliver
// (and once after the passes, for the flattest of them, a star from the
// deepest point of a shell's kernel: rescue_flat_slivers).
// The candidates are centroids of the sliver, of the cavity, of each
// cavity tetrahedron, and points above the sliver's constraint faces,
// judged exactly before anything changes: every face of the cavity's
// boundary must see the point strictly (so the star is valid and the
// point is strictly inside the region, never on the surface). A star that
// still keeps a sliver must also keep the cavity's smallest dihedral
// angle (the radius ratio can rise while it falls).
#pragma once

#include <cstddef>
#include <vector>

#include "refine/refine_context.hpp"

namespace cbr::refine {

// Tries every tetrahedron of the bounded regions with radius ratio below
// `threshold` that changed, or has a face neighbour that changed, since the
// previous pass (RefineContext::changed_near: the others failed then and
// would fail again); returns the number of points inserted, and adds the
// cavities it did not rate (a face of their boundary caps every star below
// the bar: radius_ratio_bound_for_face) to stats.sliver_cavities_skipped.
// `left_alone` (one flag per vertex), when given: the tetrahedra with a
// flagged corner are not tried (refine_mesh flags the Steiner points and
// the non-input points of their balls).
std::size_t remove_slivers(RefineContext& c, double threshold, RefineStats& stats,
                           const std::vector<char>* left_alone = nullptr);

// The last resort, once, after the optimisation passes: a flat sliver of
// four input points (radius ratio under 1e-6) that remove_slivers left
// gets the best point of the shells of its widest edges, found from the
// deepest point of their kernel too (deepest_point.hpp), if its star is
// a hundred times better than the shell and reaches 1e-4. Such stars keep
// slivers (needle-shaped input triangles bound every tetrahedron on
// them), so in the passes they would be taken up again and again and
// multiply (feeder body: 139,181 -> 155,846 tetrahedra); here nothing
// revisits them. Returns the number of points inserted (skipped cavities
// counted as by remove_slivers).
std::size_t rescue_flat_slivers(RefineContext& c, double threshold, RefineStats& stats);

// After rescue_flat_slivers, for Table II's minimum dihedral angle: a
// tetrahedron of four input points with a dihedral angle below
// `below_degrees` gets the best point of the shells of its widest edges
// judged by the smallest dihedral angle, if its star beats the shell's
// smallest angle and makes no tetrahedron under both `threshold` and the
// shell's worst radius ratio. Returns the number of points inserted;
// `log`, for tests, gets each one's replaced tetrahedra and star.
std::size_t rescue_small_angles(RefineContext& c, double below_degrees, double threshold, RefineStats& stats,
                                std::vector<TetChange>* log = nullptr);

}  // namespace cbr::refine

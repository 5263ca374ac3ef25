// The angle phase of refinement, after the optimisation passes: flips for
// the smallest dihedral angles, then rounds of points moved for the angle,
// each followed by those flips again (refine_mesh).
#pragma once

#include <cstdint>
#include <vector>

#include "refine/refine_context.hpp"
#include "refine/refine_options.hpp"

namespace cbr::refine {

// One call of improve_dihedrals_by_flips in the phase, for tests: the pass
// it was given as `since` (0: every tetrahedron) and its last sweep's.
struct DihedralCall {
    std::uint32_t since = 0;
    std::uint32_t last_sweep = 0;
};

// Runs the phase as `options` ask (flips, dihedral_flips,
// dihedral_smoothing), adding its flips and moves to `stats`.
// `keep_radius_ratio` is the radius ratio that the flips and moves keep
// (improve_dihedrals_by_flips, smooth_for_dihedrals). The first flips
// look at every tetrahedron; each later call first at what changed since
// the last sweep of the call before it. `calls`, for tests, gets every
// call in order.
void improve_angles(RefineContext& c, const RefineOptions& options, double keep_radius_ratio, RefineStats& stats,
                    std::vector<DihedralCall>* calls = nullptr);

}  // namespace cbr::refine

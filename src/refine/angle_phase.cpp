#include "refine/angle_phase.hpp"

#include "refine/quality_flips.hpp"
#include "refine/smoothing.hpp"

namespace cbr::refine {
namespace {

// Flips for the smallest dihedral angles (Table II's minimum, which
// radius-ratio flips and smoothing leave where they cannot raise the
// radius ratio): the tetrahedra below this angle, in at most this many
// sweeps.
constexpr double kDihedralFlipsBelow = 5.0;
constexpr int kDihedralFlipSweeps = 8;
// Rounds of points moved for the angle, each followed by those flips:
// later rounds start where the earlier moves and flips left the balls
// (on the 37 shared surfaces, 3 rounds instead of 1: 187 fewer
// tetrahedra under q = 0.1; thingiverse-mouth 3.4 -> 3.9 deg).
constexpr int kDihedralSmoothingRounds = 3;

}  // namespace

void improve_angles(RefineContext& c, const RefineOptions& options, double keep_radius_ratio, RefineStats& stats,
                    std::vector<DihedralCall>* calls) {
    if (!options.flips || !options.dihedral_flips) return;
    // After the first call, each looks first at what changed since the
    // last sweep of the one before (the moves in between, and that
    // sweep's own flips). thingiverse-feeder-body: the first sweeps of
    // the three later calls tried 4,589, 4,096 and 3,908 tetrahedra
    // under the angle, now 2,656, 1,824 and 1,323 (0.36 -> 0.25 s);
    // on the 37 shared surfaces only the feeder body (4 more
    // tetrahedra) and the guide arm (2 more under q = 0.1) changed.
    std::uint32_t flips_since = 0;
    const auto flips_for_angles = [&] {
        DihedralCall call{flips_since, 0};
        const DihedralFlips done = improve_dihedrals_by_flips(c, kDihedralFlipsBelow, keep_radius_ratio,
                                                              kDihedralFlipSweeps, nullptr, call.since);
        call.last_sweep = done.last_sweep;
        stats.flips += done.flips;
        stats.removal_pairs += done.after_another;
        if (calls) calls->push_back(call);
        flips_since = done.last_sweep;
    };
    flips_for_angles();
    // Then the points moved for the angle, which opens flips again
    // (everywhere: a pair of removals may reach past the moved points'
    // neighbours; thingiverse-chain-link keeps a flat tetrahedron of input
    // points at 1.5e-4 deg when the flips look only next to them), and the
    // flips open moves again, for at most kDihedralSmoothingRounds rounds.
    std::uint32_t since = 0;  // the first round tries every ball; the later ones those changed since
    for (int round = 0; round < kDihedralSmoothingRounds && options.dihedral_smoothing; ++round) {
        c.start_pass();
        const std::uint32_t now = c.pass();
        const std::size_t moved = smooth_for_dihedrals(c, kDihedralFlipsBelow, keep_radius_ratio, nullptr, since);
        since = now;
        stats.smoothed += moved;
        stats.dihedral_moves += moved;
        if (moved == 0) break;
        flips_for_angles();
    }
}

}  // namespace cbr::refine

// §5.1 first step of the combined recovery: recover missing faces by flips
// alone. For each missing face, its missing edges first (remove, by a 2-3
// flip or an edge removal, the first face or edge that the segment
// crosses, walking from either end; in the later rounds any crossing along
// the segment), then the face (remove the mesh edges that cross its
// interior). Edge removals may first remove edges of the shell (nested, to
// a depth and within a budget per face that grow from round to round; the
// rounds are in flip_recovery.cpp). Input edges are never flipped away and
// replace_tets never removes a recovered face, so a recovered constraint
// stays recovered ("protection").
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"

namespace cbr::recover {

// Whether searches that are known to fail are skipped (FailedRings,
// FailedSearches). Skipping changes nothing but the time: kOff is there
// for the test that proves it.
enum class FlipMemo { kOn, kOff };

// Whether the last, deepest round of searches runs (flip_recovery.cpp,
// kSearches, its two stages): it recovers faces that would otherwise need
// Steiner points, at most of the flips' time on the hard shared surfaces.
enum class FlipRounds { kAll, kWithoutDeepest };

// Which way a face's edges are walked: as the triangle (a, b, c) lists
// them (a-b, b-c, c-a; each edge's first crossing looked for from its
// first end first), or as its reverse (a, c, b) lists them. Searches that
// fail can still change the mesh, so the order matters; on some nearly
// cospherical CAD parts the flips recover nearly every face one way and
// a third of them the other (recovery.cpp, kFlipRestartShare).
enum class FlipDirection { kAsGiven, kReversed };

// Which ring vertices a nested edge removal (an edge from u or v to a
// ring vertex removed first, so that uv's ring loses that vertex) tries
// first: those where the ring is not convex as seen from u and v
// (mesh::ring_positions_blocking_first), or the ring's own order, the
// order before session 33. Measured on the 37 shared surfaces (recovery
// benchmark, same hour): the flips recover 71,874 of the 72,565 faces
// missing after Delaunay instead of 71,753; the feeder body's recovery
// takes 4.6 s instead of 10.5 (its flips recover 5,823 faces instead of
// 5,656), the upsampled box's 1.2 s instead of 1.3, and all 37 14.3 s
// instead of 22.2; Steiner points inside the domain 141 -> 147 (golf
// ball 6 -> 15, upsampled box 48 -> 55, octocat 19 -> 15, chain link 4 ->
// 2), all of them 192 -> 185. Tests set kRing to reach the mesh states
// that the steps after the flips were made for.
enum class NestedOrder { kBlockingFirst, kRing };

// Tries to recover the faces `missing` (indices into `faces`); marks the
// recovered ones as constraint faces; returns those still missing, in
// increasing order. `deepest_budget`: 0, the deepest round of kSearches
// (1,500 edge removals a face, then 40,000 for the faces left while the
// round has spent less than 80,000 in all); otherwise one deepest round of
// that many removals a face in its first pass, with no limit on the
// round. The retries after a failure take the second (recovery.hpp,
// kRetryFlipBudgets), and tests vary it to reach the other mesh states
// that flips can leave to the later steps. `per_round`, when given: what
// each round did (FlipRoundReport).
struct FlipRoundReport {
    std::size_t faces = 0;     // faces still missing when the round began
    std::size_t attempts = 0;  // attempts at a face, every pass together
    // Edge removals spent, every face and pass together (a search known
    // to fail counts what it spent when it ran).
    long removals = 0;
};
std::vector<std::size_t> recover_by_flips(mesh::TetMesh& m, const ConstraintFaces& faces,
                                          const std::vector<std::size_t>& missing, FlipMemo memo = FlipMemo::kOn,
                                          FlipRounds rounds = FlipRounds::kAll, int deepest_budget = 0,
                                          FlipDirection direction = FlipDirection::kAsGiven,
                                          NestedOrder nested = NestedOrder::kBlockingFirst,
                                          std::vector<FlipRoundReport>* per_round = nullptr);

}  // namespace cbr::recover

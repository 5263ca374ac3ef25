// Constrained boundary recovery (Du & Wang 2004, §5): the driver. Steps, in
// order: find the missing faces; flips (§5.1); where flips are blocked,
// interior Steiner points off the surface and the flips again on those
// faces (unblocking_points.hpp); per remaining face, conforming recovery
// then edge- and face-added-point splitting (§5.2-5.4), tried again in
// other orders of the faces after a failure, and again with other
// unblocking points (of any star, denser); Steiner suppression and
// repositioning (§6). A face that a step cannot recover is reported,
// never hidden.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"
#include "recover/flip_recovery.hpp"

namespace cbr::recover {

// The rows of the paper's Table I that recovery fills.
struct RecoveryStats {
    std::size_t missing_faces = 0;       // after Delaunay
    std::size_t recovered_by_flips = 0;
    std::size_t conforming_points = 0;   // added on the surface, then split off
    std::size_t steiner_generated = 0;   // unblocking points, then split-off points
    std::size_t steiner_remaining = 0;
};

struct RecoveryResult {
    bool ok = false;
    std::vector<std::size_t> unrecovered;  // input triangles that are not faces
    std::vector<std::string> invalid;      // whole-mesh check failures (a bug if not empty)
    std::string why;                       // when !ok: the step that gave up, and why
    // Steiner points left in the mesh, in increasing id order; they are the
    // vertices after the input ones (ids input_count, input_count + 1, ...).
    std::vector<mesh::VertexId> steiner;
};

struct RecoveryOptions {
    // The deepest round of flip searches before the interior Steiner points
    // (CBR_PARAM_RECOVERY_DEEP_FLIPS): fewer Steiner points, more time.
    bool deep_flips = true;
    // Edge removals a face in that round (0: the two stages of
    // flip_recovery.cpp, kSearches; otherwise one round of that many a
    // face). Not in the C API: the retries and the tests vary it to reach
    // other mesh states for the steps after the flips.
    int deepest_flip_budget = 0;
    // cbr_mesh_recover_faces (api_recover.cpp, recover_in_attempts), after
    // a failure: recovery again with the eight corners of an enclosing box
    // added, then from the Delaunay mesh with the deepest flip round's
    // budget at each of kRetryFlipBudgets, outside the box and inside it.
    // CBR_PARAM_RECOVERY_RETRIES.
    bool retries = true;
    // Orders of the faces that conforming recovery and splitting try, each
    // from the mesh the flips left (recovery.cpp, recover_in_face_orders).
    // Not in the C API: tests set 1 to reach the first order's failures.
    int face_orders = 6;
    // After a failure: again from the mesh the flips left with other
    // unblocking points (recovery.cpp, kUnblockingTries: without the star
    // limit when it turned points away, then denser points nearer the
    // faces, then the dense and the densest points kept even where they
    // do not cut the crossings); at most this many of those tries in all
    // (the first is the default). Not in the C API: tests lower it to
    // reach the failures of the first tries.
    int unblocking_tries = 6;
    // Which ring vertices the flips' nested edge removals try first
    // (flip_recovery.hpp). Not in the C API: tests set kRing to reach the
    // mesh states that the later steps were made for.
    NestedOrder nested_order = NestedOrder::kBlockingFirst;
    // Threads the passes that only read the whole mesh may use (the
    // validity check at the end; mesh/chunks.hpp): the same result with
    // any number. CBR_PARAM_THREADS.
    int threads = 1;
};

// The budgets of the deepest flip round (edge removals a face) that
// cbr_mesh_recover_faces tries after a failure with the default one, in
// this order (see RecoveryOptions::retries).
inline constexpr int kRetryFlipBudgets[] = {10000, 30000};
// A flip state that cbr_mesh_recover_faces starts again from after a
// failure: the deepest flip round's budget (0: the options' own) and the
// order of the nested edge removals. The retries run in ring order, the
// flip states of every attempt before session 33 (the options' budget,
// then those above): the blocking vertices first recover more faces by
// flips (fewer Steiner points, less time), but the mesh they leave is
// another one, and on turned CAD parts the steps after the flips fail in
// some flip states and not in others (rotate_surface.py seed 11 of
// thingicsg-openscad-example012 and of the feeder guide arm fail with the
// blocking vertices first and recover in the old states).
struct FlipState {
    int deepest_budget = 0;
    NestedOrder nested = NestedOrder::kBlockingFirst;
};

// The unblocking tries of the flip states with those other budgets (the
// ring-order state gets them all, as the first attempts had): the first
// two, without the denser points (they had their chance in the default
// flip state; on the turned feeder body, which fails in every attempt,
// they took the time to fail from 88 to 167 s when every attempt had
// them).
inline constexpr int kRetryUnblockingTries = 2;

// The unblocking tries of the retries in the other states with the
// options' budget (inside the enclosing box, the ring order): all but the
// last, the densest points kept where they do not cut. The copies that
// try recovers (turned or jittered CAD plates) recover in the first
// attempt; on the turned feeder body, which fails in every attempt, it
// took the time to fail from 127 to 168 s when every such attempt had
// it, and costs 1 s in the first attempt alone (11.7 -> 12.7 s).
inline constexpr int kRetryLastUnblockingTries = RecoveryOptions{}.unblocking_tries - 1;

// Recovers every triangle of `faces` as a face of m, marking them as
// constraint faces. Steiner points are appended to m's vertices; ids below
// the vertex count on entry never change. On failure m may have been
// modified: the caller restores it. m must be a Delaunay mesh on entry;
// `delaunay_again`, when given, makes m that mesh once more (recovery.cpp,
// kFlipRestartShare: the flips may run again from it). `present`, when
// given, is facets_of_mesh of the triangles on m as it is on entry (the
// surface check's): the faces present are marked from it
// (mark_present_faces).
RecoveryResult recover_faces(mesh::TetMesh& m, const ConstraintFaces& faces, RecoveryStats& stats,
                             const RecoveryOptions& options = {},
                             const std::function<void()>& delaunay_again = {},
                             const std::vector<mesh::FacetRef>* present = nullptr);

}  // namespace cbr::recover

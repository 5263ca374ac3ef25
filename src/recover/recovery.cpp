#include "recover/recovery.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <iterator>
#include <string>

#include "mesh/mesh_check.hpp"
#include "mesh/vertex_compaction.hpp"
#include "recover/conforming.hpp"
#include "recover/flip_recovery.hpp"
#include "recover/split_passes.hpp"
#include "recover/steiner_merging.hpp"
#include "recover/steiner_repositioning.hpp"
#include "recover/steiner_suppression.hpp"
#include "recover/surface_points.hpp"
#include "recover/unblocking_points.hpp"

namespace cbr::recover {
namespace {

// §5.2-5.4 for the faces flips left: conforming recovery of every one of
// them first (so that every triangle at an added point has its fan when
// the point is split), then the splitting of every added point, those on
// edges first (§5.3), then those inside faces (§5.4).
bool recover_by_splitting(mesh::TetMesh& m, const ConstraintFaces& faces, const std::vector<std::size_t>& missing,
                          RecoveryStats& stats, RecoveryResult& result) {
    SurfacePoints points(faces, m.vertex_count());
    ConformingRecovery conforming(m, points);
    for (std::size_t f : missing) {
        if (!conforming.recover_face(f)) {
            result.why = "conforming recovery of triangle " + std::to_string(f) + ": " + conforming.why();
            stats.conforming_points = points.added_in_order().size();
            return false;
        }
    }
    const std::vector<mesh::VertexId> added = points.added_in_order();
    stats.conforming_points = added.size();
    std::size_t made = 0;
    std::string why;
    const bool split = split_added_points(m, points, conforming.incident(), added, result.steiner, made, why);
    stats.steiner_generated += made;
    if (!split) result.why = "splitting an added point: " + why;
    return split;
}

// What a retry starts again from: the mesh, the statistics and the
// Steiner points as they were.
struct Checkpoint {
    Checkpoint(const mesh::TetMesh& m, const RecoveryStats& s, const RecoveryResult& r)
        : mesh(m), stats(s), steiner(r.steiner) {}
    void restore(mesh::TetMesh& m, RecoveryStats& s, RecoveryResult& r) const {
        m = mesh;
        s = stats;
        r.steiner = steiner;
    }
    const mesh::TetMesh mesh;
    const RecoveryStats stats;
    const std::vector<mesh::VertexId> steiner;
};

// What a failed attempt reported. Recovery reports a failure as its first
// attempt's (statistics and reason), whatever the retries gave.
struct FailureReport {
    RecoveryStats stats;
    std::string why;
    void restore(RecoveryStats& s, RecoveryResult& r) const {
        s = stats;
        r.why = why;
    }
};

// Attempt k's order of the faces the flips left: as they are, reversed,
// then shuffled (Fisher-Yates on a fixed linear congruential sequence: the
// same orders on every platform, which std::shuffle does not promise).
std::vector<std::size_t> face_order(std::vector<std::size_t> faces, int attempt) {
    if (attempt == 1) std::reverse(faces.begin(), faces.end());
    if (attempt < 2) return faces;
    std::uint32_t x = static_cast<std::uint32_t>(attempt);
    for (std::size_t i = faces.size(); i > 1; --i) {
        x = x * 1103515245u + 12345u;
        std::swap(faces[i - 1], faces[(x >> 8) % i]);
    }
    return faces;
}

// §5.2 leaves the order of the faces open, and where the surface is nearly
// flat over many faces it matters: the points added on one face's edges
// are rounded, and the next face's crossings meet them in flat
// tetrahedra that one order can clear and another cannot (turned copies of
// a CAD cylinder and of the upsampled box, the feeder body shifted by 1e6
// and 1e8: each fails in the first order, recovers in a later one). So
// after a failure the mesh the flips left is restored and the faces go
// again in the next order, up to options.face_orders orders. A failure is
// reported as the first order's (its reason and its statistics).
bool recover_in_face_orders(mesh::TetMesh& m, const ConstraintFaces& faces, const std::vector<std::size_t>& missing,
                            int orders, RecoveryStats& stats, RecoveryResult& result) {
    const Checkpoint before(m, stats, result);
    FailureReport first_failure;
    for (int attempt = 0; attempt < std::max(orders, 1); ++attempt) {
        if (attempt > 0) before.restore(m, stats, result);
        if (recover_by_splitting(m, faces, face_order(missing, attempt), stats, result)) return true;
        if (attempt == 0) first_failure = {stats, result.why};
    }
    first_failure.restore(stats, result);
    if (orders > 1) result.why += " (and in " + std::to_string(orders - 1) + " other orders of the faces)";
    return false;
}

// Where the first flips left faces: interior points that unblock the flips
// (placed as `unblocking` says), the flips again, up to `rounds` times
// while faces are left and the last round kept a point, then conforming
// recovery and splitting of what is still missing, in other orders of the
// faces after a failure. `missing`: in, the faces the first flips left;
// out, those still missing after the last flips. False (result.why set)
// when conforming recovery or splitting failed; `star_refused`: whether the
// star limit turned an unblocking point away.
bool unblock_then_split(mesh::TetMesh& m, const ConstraintFaces& faces, std::vector<std::size_t>& missing,
                        const UnblockingOptions& unblocking_options, int rounds, int face_orders,
                        FlipDirection direction, NestedOrder nested, RecoveryStats& stats, RecoveryResult& result,
                        bool& star_refused) {
    std::size_t kept = 0;
    star_refused = false;
    for (int round = 0; round < rounds && !missing.empty(); ++round) {
        const UnblockingResult unblocking =
            insert_unblocking_points(m, faces, missing, result.steiner, unblocking_options);
        star_refused = star_refused || unblocking.refused_for_star > 0;
        stats.steiner_generated += unblocking.kept;
        kept += unblocking.kept;
        if (unblocking.kept == 0) break;
        missing = recover_by_flips(m, faces, missing, FlipMemo::kOn, FlipRounds::kWithoutDeepest, 0, direction,
                                   nested);
    }
    // §6 before conforming recovery: the points that the recovered faces
    // do not need go (they are marked, so none is lost); near the faces
    // still missing, the points left would make thin tetrahedra for the
    // points conforming recovery adds and their splitting (feeder body:
    // with them, conforming recovery fails; without, it adds 6,948
    // points, where it added 42,202 on the mesh of the flips alone
    // before it failed).
    if (kept > 0 && !missing.empty()) suppress_vertices(m, result.steiner);
    return missing.empty() || recover_in_face_orders(m, faces, missing, face_orders, stats, result);
}

// The unblocking points tried, in order, each from the mesh the flips
// left, until one leads to every face (recover_after_flips). A try marked
// `after_star_refusal` runs only when the try before it had points turned
// away by the star limit: without the limit it would place the same
// points.
struct UnblockingTry {
    UnblockingOptions options;
    bool after_star_refusal;
    int rounds = 1;  // of points then flips (unblock_then_split)
};
// `placement` with no limit on the stars.
constexpr UnblockingOptions of_any_star(UnblockingOptions placement) {
    placement.max_star = kUnblockingAnyStar;
    return placement;
}
// `placement` with the first point of each target kept and the walk to a
// point free to pass recovered faces.
constexpr UnblockingOptions first_kept(UnblockingOptions placement) {
    placement.keep_first = true;
    placement.walk_through_recovered = true;
    return placement;
}
constexpr UnblockingTry kUnblockingTries[] = {
    // The default: stars of at most kUnblockingMaxStar tetrahedra.
    {UnblockingOptions{}, false},
    // No star limit. On a nearly flat fanned cap (CAD cylinders turned in
    // space) the points that unblock the flips see most of the cap, and
    // their stars are large; with them, the flips recover faces whose
    // conforming recovery fails on rounded points (turned prisms with
    // fanned caps: 18 of 24 failures recover so, most with no conforming
    // point at all). The limit stays for the first try: a point of a large
    // star costs §6 suppression time (the shared cylinder: 0.1 s -> 0.4 s
    // without it), and a surface that recovers in the first try gets the
    // same mesh as before.
    {of_any_star(UnblockingOptions{}), true},
    // Denser points, nearer the faces (kDenseUnblocking), then the same
    // without the star limit.
    {kDenseUnblocking, false},
    {of_any_star(kDenseUnblocking), true},
    // Last, the dense points kept whether or not they cut the crossings
    // (UnblockingOptions::keep_first). In a nearly planar region of many
    // input triangles (a CAD plate turned in space) a point that only
    // moves a missing edge's crossings still puts tetrahedra off the plane
    // for the flips, where the tries above turned nearly all their points
    // away: thingiverse-feeder-guide-arm turned by rotate_surface.py seed
    // 41 (a plate of 444 triangles) then recovers in the first attempt,
    // with 3 Steiner points inside, where every attempt failed before
    // (TetGen recovers it). The same try with the default points did not.
    // Its points may lie across a recovered face from the crossed
    // tetrahedra (UnblockingOptions::walk_through_recovered), and it runs
    // up to three rounds of points and flips: the same part turned by seed
    // 51 (a plate of 444 triangles again) kept 30 points in a first round
    // that left 4 faces, and no point at all near the last 2 while the
    // walk stopped at recovered faces; with both, the second round (5
    // points) lets the flips recover every face, with no conforming point
    // (TetGen recovers it too).
    {first_kept(kDenseUnblocking), false, 3},
    // Then the same with twice as many points (kDensestUnblocking): which
    // density lets the flips recover a plate's last faces varies from
    // plate to plate. The guide arm turned by seed 91 fails with the dense
    // points in every attempt (splitting an added point on the plate's
    // last 2 faces: "no Steiner point position sees the whole wedge") and
    // recovers with these in its first attempt, 5 Steiner points inside
    // (TetGen 52; the default points recover it too); the same part with
    // every point jittered (run_mutation_sweep.py seed 44, case 298)
    // recovers with these only, 2 Steiner points inside (tetgen -pYQ exits
    // 0 with 4 input triangles missing). Seed 41 needs the dense ones.
    // cbr_mesh_recover_faces's retries leave this try out
    // (kRetryLastUnblockingTries).
    {first_kept(kDensestUnblocking), false, 3},
};

static_assert(std::size(kUnblockingTries) == static_cast<std::size_t>(RecoveryOptions{}.unblocking_tries),
              "by default every unblocking try may run");

// unblock_then_split with each of the first options.unblocking_tries of
// kUnblockingTries in turn, from the mesh the flips left, until one
// succeeds. A failure is reported as the first try's (its reason,
// statistics and faces), with the number of other tries added.
bool recover_after_flips(mesh::TetMesh& m, const ConstraintFaces& faces, std::vector<std::size_t>& missing,
                         const RecoveryOptions& options, FlipDirection direction, RecoveryStats& stats,
                         RecoveryResult& result) {
    const Checkpoint flipped(m, stats, result);
    const std::vector<std::size_t> flips_left = missing;
    FailureReport first_failure;
    std::vector<std::size_t> first_missing;
    bool star_refused = false;
    int tried = 0;
    const std::size_t tries = std::min<std::size_t>(std::size(kUnblockingTries),
                                                    static_cast<std::size_t>(std::max(options.unblocking_tries, 1)));
    for (std::size_t k = 0; k < tries; ++k) {
        const UnblockingTry& attempt = kUnblockingTries[k];
        if (attempt.after_star_refusal && !star_refused) continue;
        if (tried > 0) {
            flipped.restore(m, stats, result);
            missing = flips_left;
        }
        if (unblock_then_split(m, faces, missing, attempt.options, attempt.rounds, options.face_orders, direction,
                               options.nested_order, stats, result, star_refused))
            return true;
        if (tried++ == 0) {
            first_failure = {stats, result.why};
            first_missing = missing;
        }
    }
    first_failure.restore(stats, result);
    if (tried > 1) result.why += " (and with " + std::to_string(tried - 1) + " other placements of unblocking points)";
    missing = first_missing;
    return false;
}

// §5.1 leaves open the order in which a face's edges are recovered, and
// searches that fail can still change the mesh. On a nearly cospherical
// CAD part (thingicsg-cylinder: 400 points on two circles, caps fanned
// from one rim vertex) the flips recover all but 4 of its 596 missing
// faces walking each triangle as given, but leave 390 of them on its
// mirror image (x -> -x), whose recovery then took 121 s and kept 95
// Steiner points; walking each triangle reversed, 2 (2-3 s, 1 point).
// Mirrored in y or z or with its triangles reversed, the same: one
// direction leaves 178-390 faces, the other 2-4. So when the flips leave
// more than this share of the faces missing after Delaunay, they run again
// from the Delaunay mesh the other way, and recovery goes on from
// whichever left fewer. (On the 37 shared surfaces they leave at most
// 17%: thingiverse-mouth, 32 of 186, whose reversed flips leave 32 too;
// then the feeder body, 419 of 6,075, 7%. Mirrored in x, the mouth
// leaves 23%, 42 of 186, and 42 reversed.)
constexpr std::size_t kFlipRestartShare = 4;  // more than 1 in 4

// The first flips (recover_by_flips with the rounds and budget of
// `options`), and the restart above when `delaunay_again` can give the
// Delaunay mesh back. Returns the faces left; `direction`: the direction
// of the flips whose mesh m now holds.
std::vector<std::size_t> first_flips(mesh::TetMesh& m, const ConstraintFaces& faces,
                                     const std::vector<std::size_t>& missing, const RecoveryOptions& options,
                                     const std::function<void()>& delaunay_again, FlipDirection& direction) {
    const FlipRounds rounds = options.deep_flips ? FlipRounds::kAll : FlipRounds::kWithoutDeepest;
    direction = FlipDirection::kAsGiven;
    std::vector<std::size_t> left =
        recover_by_flips(m, faces, missing, FlipMemo::kOn, rounds, options.deepest_flip_budget, direction,
                         options.nested_order);
    if (!delaunay_again || left.size() * kFlipRestartShare <= missing.size()) return left;
    mesh::TetMesh as_given = m;  // only here: copied before every flips, igea's recovery took 8% longer
    delaunay_again();
    // The faces present after Delaunay are marked again (protected from
    // the flips); the missing ones are the same.
    const std::vector<std::size_t> again = mark_present_faces(m, faces);
    std::vector<std::size_t> reversed = recover_by_flips(m, faces, again, FlipMemo::kOn, rounds,
                                                         options.deepest_flip_budget, FlipDirection::kReversed,
                                                         options.nested_order);
    if (reversed.size() < left.size()) {
        direction = FlipDirection::kReversed;
        return reversed;
    }
    m = std::move(as_given);
    return left;
}

}  // namespace

RecoveryResult recover_faces(mesh::TetMesh& m, const ConstraintFaces& faces, RecoveryStats& stats,
                             const RecoveryOptions& options, const std::function<void()>& delaunay_again,
                             const std::vector<mesh::FacetRef>* present) {
    RecoveryResult result;
    const std::size_t input_vertices = m.vertex_count();
    std::vector<std::size_t> missing = mark_present_faces(m, faces, present);
    stats = RecoveryStats{};
    stats.missing_faces = missing.size();

    // §5.1: flips first. Where they are blocked, interior Steiner points
    // off the surface (kept in result.steiner for §6), then the flips again
    // on every face still missing (a point near one face also unblocks its
    // neighbours: on the upsampled box 62 points let the flips recover 202
    // of 208 faces, where the faces that got a point alone give 62). Table
    // I's "recovered by flips" counts the flips alone (the faces recovered
    // after the points needed Steiner points); the points count as Steiner
    // points generated. More rounds converge slowly (feeder body: 419 ->
    // 172 -> 143 -> 133 ... 123 faces after six) for their time. The
    // second run leaves out the deepest round: the faces it would still
    // recover cost conforming recovery less (feeder body: 2.8 s for 27
    // faces; Steiner points inside on the hard surfaces 148 -> 149).
    const std::size_t missing_after_delaunay = missing.size();
    FlipDirection direction = FlipDirection::kAsGiven;
    missing = first_flips(m, faces, missing, options, delaunay_again, direction);
    stats.recovered_by_flips = missing_after_delaunay - missing.size();
    if (!missing.empty()) {
        if (!recover_after_flips(m, faces, missing, options, direction, stats, result)) {
            result.unrecovered = std::move(missing);
            return result;
        }
        // Conforming recovery ran when the second flips left faces: it
        // recovered every face it was given (checked again here).
        if (!missing.empty()) {
            missing = mark_present_faces(m, faces);
            if (!missing.empty()) result.why = "faces still missing after every added point was split";
        }
    }
    if (!result.steiner.empty()) {
        // §6 (also when the flips recovered every face after the unblocking
        // points): Steiner points removed where their ball can be rebuilt
        // without them (the recovered faces are marked, so no change can
        // lose one), then in pairs (two balls coned from one point; a
        // merged point may then go alone), the others moved to where their
        // tetrahedra are best.
        suppress_vertices(m, result.steiner);
        if (merge_steiner_pairs(m, result.steiner) > 0) suppress_vertices(m, result.steiner);
        RepositionOptions reposition;
        reposition.all_faces_present = missing.empty();
        reposition_steiner_points(m, result.steiner, faces, reposition);
    }
    mesh::compact_vertices_from(m, input_vertices, result.steiner);
    stats.steiner_remaining = result.steiner.size();

    result.unrecovered = std::move(missing);
    // Whatever the steps did, the mesh must be valid before it is reported
    // as recovered (recovery.md, "Invariants"): exact, once, at the end.
    const mesh::CheckReport report = mesh::check_mesh(m, options.threads);
    result.invalid = report.errors;
    result.ok = result.unrecovered.empty() && report.ok();
    return result;
}

}  // namespace cbr::recover

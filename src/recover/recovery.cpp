#include "recover/recovery.hpp"

#include "mesh/mesh_check.hpp"
#include "mesh/vertex_compaction.hpp"
#include "recover/conforming.hpp"
#include "recover/flip_recovery.hpp"
#include "recover/point_splitting.hpp"
#include "recover/steiner_merging.hpp"
#include "recover/steiner_repositioning.hpp"
#include "recover/steiner_suppression.hpp"
#include "recover/surface_points.hpp"

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
    PointSplitting splitting(m, points, conforming.incident());
    for (const bool edges : {true, false}) {
        for (mesh::VertexId e : added) {
            if (!points.is_added(e) || points.on_edge(e, nullptr, nullptr, nullptr) != edges) continue;
            if (!splitting.split(e, result.steiner)) {
                result.why = "splitting an added point: " + splitting.why();
                return false;
            }
        }
    }
    stats.steiner_generated = splitting.made();
    return true;
}

}  // namespace

RecoveryResult recover_faces(mesh::TetMesh& m, const ConstraintFaces& faces, RecoveryStats& stats) {
    RecoveryResult result;
    const std::size_t input_vertices = m.vertex_count();
    std::vector<std::size_t> missing = mark_present_faces(m, faces);
    stats = RecoveryStats{};
    stats.missing_faces = missing.size();

    // §5.1: flips first.
    const std::vector<std::size_t> after_flips = recover_by_flips(m, faces, missing);
    stats.recovered_by_flips = missing.size() - after_flips.size();
    missing = after_flips;

    if (!missing.empty()) {
        if (!recover_by_splitting(m, faces, missing, stats, result)) {
            result.unrecovered = std::move(missing);
            return result;
        }
        missing = mark_present_faces(m, faces);
        if (!missing.empty()) result.why = "faces still missing after every added point was split";
        // §6: Steiner points removed where their ball can be rebuilt without
        // them (the recovered faces are marked, so no change can lose one),
        // then in pairs (two balls coned from one point; a merged point may
        // then go alone), the others moved to where their tetrahedra are
        // best.
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
    const mesh::CheckReport report = mesh::check_mesh(m);
    result.invalid = report.errors;
    result.ok = result.unrecovered.empty() && report.ok();
    return result;
}

}  // namespace cbr::recover

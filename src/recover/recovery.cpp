#include "recover/recovery.hpp"

#include "mesh/mesh_check.hpp"
#include "recover/flip_recovery.hpp"

namespace cbr::recover {

RecoveryResult recover_faces(mesh::TetMesh& m, const ConstraintFaces& faces, RecoveryStats& stats) {
    RecoveryResult result;
    std::vector<std::size_t> missing = mark_present_faces(m, faces);
    stats = RecoveryStats{};
    stats.missing_faces = missing.size();

    // §5.1: flips first.
    const std::vector<std::size_t> after_flips = recover_by_flips(m, faces, missing);
    stats.recovered_by_flips = missing.size() - after_flips.size();
    missing = after_flips;

    // Conforming recovery with point splitting (§5.2-5.4) reduces `missing`
    // here.

    result.unrecovered = std::move(missing);
    // Whatever the steps did, the mesh must be valid before it is reported
    // as recovered (recovery.md, "Invariants"): exact, once, at the end.
    const mesh::CheckReport report = mesh::check_mesh(m);
    result.invalid = report.errors;
    result.ok = result.unrecovered.empty() && report.ok();
    return result;
}

}  // namespace cbr::recover

#include "recover/recovery.hpp"

#include "mesh/mesh_check.hpp"

namespace cbr::recover {

RecoveryResult recover_faces(mesh::TetMesh& m, const ConstraintFaces& faces, RecoveryStats& stats) {
    RecoveryResult result;
    std::vector<std::size_t> missing = mark_present_faces(m, faces);
    stats = RecoveryStats{};
    stats.missing_faces = missing.size();

    // Flips (§5.1) and conforming recovery with point splitting (§5.2-5.4)
    // reduce `missing` here.

    result.unrecovered = std::move(missing);
    // Whatever the steps did, the mesh must be valid before it is reported
    // as recovered (recovery.md, "Invariants"): exact, once, at the end.
    const mesh::CheckReport report = mesh::check_mesh(m);
    result.invalid = report.errors;
    result.ok = result.unrecovered.empty() && report.ok();
    return result;
}

}  // namespace cbr::recover

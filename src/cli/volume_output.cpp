#include "cli/volume_output.hpp"

#include <cstdint>
#include <vector>

namespace cbr::cli {
namespace {

// Leaves out the points after the input's that no tetrahedron uses: the
// Steiner points of the exterior, dropped with it (the library keeps
// them: cbr_mesh_point_count), which a solver reading the file would
// otherwise meet as nodes of no element. The input's points keep their
// ids (an open surface's, used by no tetrahedron, too); the points after
// them keep their order.
void drop_unused_points_after(std::size_t input_points, io::VolumeMesh& v) {
    const std::size_t n = v.num_points();
    std::vector<char> used(n, 0);
    for (std::int64_t id : v.tets) used[static_cast<std::size_t>(id)] = 1;
    std::vector<std::int64_t> renumbered(n, -1);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (i >= input_points && !used[i]) continue;
        renumbered[i] = static_cast<std::int64_t>(kept);
        for (std::size_t k = 0; k < 3; ++k) v.xyz[3 * kept + k] = v.xyz[3 * i + k];
        if (!v.is_steiner.empty()) v.is_steiner[kept] = v.is_steiner[i];
        ++kept;
    }
    if (kept == n) return;
    v.xyz.resize(3 * kept);
    if (!v.is_steiner.empty()) v.is_steiner.resize(kept);
    for (std::int64_t& id : v.tets) id = renumbered[static_cast<std::size_t>(id)];
}

}  // namespace

int collect_volume(const cbr_mesh* m, const io::SurfaceMesh& surface, io::VolumeMesh& out) {
    const std::int64_t np = cbr_mesh_point_count(m), nt = cbr_mesh_tet_count(m), ns = cbr_mesh_steiner_count(m);
    if (np < 0 || nt < 0 || ns < 0) return CBR_ERR_INTERNAL;
    out.xyz.resize(3 * static_cast<std::size_t>(np));
    out.tets.resize(4 * static_cast<std::size_t>(nt));
    out.tet_regions.resize(static_cast<std::size_t>(nt));
    std::vector<std::int64_t> steiner(static_cast<std::size_t>(ns));
    int status = cbr_mesh_get_points(m, out.xyz.data());
    if (status == CBR_OK) status = cbr_mesh_get_tets(m, out.tets.data());
    if (status == CBR_OK) status = cbr_mesh_get_tet_regions(m, out.tet_regions.data());
    if (status == CBR_OK) status = cbr_mesh_steiner_points(m, steiner.data());
    if (status != CBR_OK) return status;
    out.tris = surface.tris;
    out.tri_labels = surface.labels;
    out.tri_labels.resize(surface.tris.size() / 3, 0);
    out.is_steiner.assign(static_cast<std::size_t>(np), 0);
    for (std::int64_t s : steiner) {
        if (s < 0 || s >= np) return CBR_ERR_INTERNAL;
        out.is_steiner[static_cast<std::size_t>(s)] = 1;
    }
    for (std::int64_t id : out.tets)
        if (id < 0 || id >= np) return CBR_ERR_INTERNAL;
    drop_unused_points_after(surface.num_points(), out);
    return CBR_OK;
}

}  // namespace cbr::cli

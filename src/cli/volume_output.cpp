#include "cli/volume_output.hpp"

#include <cstdint>
#include <vector>

#include "mesh/huge_pages.hpp"

namespace cbr::cli {

int collect_volume(const cbr_mesh* m, const io::SurfaceMesh& surface, io::VolumeMesh& out) {
    const std::int64_t np = cbr_mesh_point_count(m), nt = cbr_mesh_tet_count(m), ns = cbr_mesh_steiner_count(m);
    if (np < 0 || nt < 0 || ns < 0) return CBR_ERR_INTERNAL;
    // Filled here, then read by the writer and Table II: huge pages spare
    // igea's 27 MB of tetrahedra 7,000 page faults.
    cbr::mesh::resize_huge(out.xyz, 3 * static_cast<std::size_t>(np));
    cbr::mesh::resize_huge(out.tets, 4 * static_cast<std::size_t>(nt));
    cbr::mesh::resize_huge(out.tet_regions, static_cast<std::size_t>(nt));
    std::vector<std::int64_t> steiner(static_cast<std::size_t>(ns));
    int status = cbr_mesh_get_points(m, out.xyz.data());
    if (status == CBR_OK) status = cbr_mesh_get_tets(m, out.tets.data());
    if (status == CBR_OK) status = cbr_mesh_get_tet_regions(m, out.tet_regions.data());
    if (status == CBR_OK) status = cbr_mesh_steiner_points(m, steiner.data());
    if (status != CBR_OK) return status;
    cbr::mesh::reserve_huge(out.tris, surface.tris.size());
    out.tris.assign(surface.tris.begin(), surface.tris.end());
    out.tri_labels = surface.labels;
    out.tri_labels.resize(surface.tris.size() / 3, 0);
    out.is_steiner.assign(static_cast<std::size_t>(np), 0);
    for (std::int64_t s : steiner) {
        if (s < 0 || s >= np) return CBR_ERR_INTERNAL;
        out.is_steiner[static_cast<std::size_t>(s)] = 1;
    }
    for (std::int64_t id : out.tets)
        if (id < 0 || id >= np) return CBR_ERR_INTERNAL;
    return CBR_OK;
}

}  // namespace cbr::cli

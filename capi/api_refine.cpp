// extern "C" full mesh generation (Du & Wang 2004, §6): cbr_mesh_refine and
// the CBR_STAT_* keys of its results (Table II, counts, time).
#include <cbr/cbr.h>

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "handle.hpp"
#include "mesh/mesh_check.hpp"
#include "refine/quality_stats.hpp"
#include "refine/refine.hpp"

using cbr::capi::ApiError;
using cbr::capi::guarded;
using cbr::capi::require;

namespace cbr::capi {

// The Table II keys, from a table (the whole mesh's or one region's).
bool table_two_stat(const cbr::refine::QualityTable& q, int key, double& value) {
    switch (key) {
        case CBR_STAT_QUALITY_AVERAGE: value = q.average; return true;
        case CBR_STAT_QUALITY_MIN: value = q.minimum; return true;
        case CBR_STAT_PERCENT_ABOVE_0_4: value = q.percent_above_0_4; return true;
        case CBR_STAT_PERCENT_BELOW_0_1: value = q.percent_below_0_1; return true;
        case CBR_STAT_BAD_TOUCHING_STEINER: value = static_cast<double>(q.bad_touching_steiner); return true;
        case CBR_STAT_DIHEDRAL_MIN: value = q.dihedral_min_deg; return true;
        case CBR_STAT_DIHEDRAL_MAX: value = q.dihedral_max_deg; return true;
        case CBR_STAT_REFINE_TETS: value = static_cast<double>(q.tets); return true;
        default: return false;
    }
}

bool refine_stat(const cbr_mesh& mesh, int key, double& value) {
    const RefineState& r = mesh.refine;
    if (table_two_stat(r.quality, key, value)) return true;
    const auto count = [](std::size_t n) { return static_cast<double>(n); };
    switch (key) {
        case CBR_STAT_FIELD_POINTS: value = count(r.stats.field_points); return true;
        case CBR_STAT_REFINE_FLIPS: value = count(r.stats.flips); return true;
        case CBR_STAT_REFINE_SECONDS: value = r.seconds; return true;
        case CBR_STAT_REFINE_OVERSIZE_TETS: value = count(r.stats.unresolved_size); return true;
        default: return false;
    }
}

}  // namespace cbr::capi

extern "C" {

CBR_API int cbr_mesh_refine(cbr_mesh* mesh) {
    return guarded(mesh, "cbr_mesh_refine", [&] {
        require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL");
        require(mesh->recovery.done, CBR_ERR_INVALID_ARGUMENT,
                "no recovered boundary: call cbr_mesh_recover_faces (successfully) first");
        cbr::refine::RefineOptions options = mesh->refine_options;
        options.threads = cbr::capi::thread_count(*mesh);
        require(options.size_from_surface || options.target_size > 0, CBR_ERR_INVALID_ARGUMENT,
                "no sizing field: CBR_PARAM_REFINE_SIZE_FROM_SURFACE is 0 and CBR_PARAM_REFINE_SIZE is 0");
        const auto start = std::chrono::steady_clock::now();
        cbr::mesh::TetMesh& m = mesh->delaunay.mesh_for_update();
        // A failed call changes nothing: work on the mesh, restore the copy
        // on any exception or failed check.
        const cbr::mesh::TetMesh backup = m;
        const cbr::capi::RecoveryState& rec = mesh->recovery;
        cbr::capi::RefineState state;
        cbr::recover::RegionMap regions;
        // Refinement may suppress Steiner points (and renumber the points
        // after the caller's): the list is replaced only on success.
        std::vector<cbr::mesh::VertexId> steiner = rec.steiner;
        try {
            state.stats = cbr::refine::refine_mesh(m, rec.faces, rec.regions.of_tet, steiner, options);
            regions = cbr::recover::classify_regions(m, rec.faces);
            const cbr::mesh::CheckReport check = cbr::mesh::check_mesh(m, cbr::capi::thread_count(*mesh));
            if (!check.ok()) throw ApiError{CBR_ERR_INTERNAL, "refinement left an invalid mesh: " + check.errors.front()};
            if (regions.count != rec.regions.count)
                throw ApiError{CBR_ERR_INTERNAL, "refinement changed the number of regions from " +
                                                     std::to_string(rec.regions.count) + " to " +
                                                     std::to_string(regions.count)};
        } catch (...) {
            m = backup;
            throw;
        }
        mesh->delaunay.adopt_added_vertices();  // new points: external id == internal id
        mesh->recovery.regions = std::move(regions);
        mesh->recovery.steiner = std::move(steiner);  // what cbr_mesh_steiner_points reports from now on
        mesh->recovery.interior =
            cbr::capi::interior_points(*mesh, mesh->recovery.interior.caller, mesh->recovery.regions.of_tet);
        state.quality = cbr::refine::measure_quality(m, mesh->recovery.regions.of_tet, rec.steiner,
                                                     cbr::capi::thread_count(*mesh), &state.region_quality);
        state.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        state.done = true;
        mesh->refine = std::move(state);
        return CBR_OK;
    });
}

CBR_API int cbr_mesh_get_region_stat(const cbr_mesh* mesh, int32_t region, int key, double* value) {
    return guarded(mesh, "cbr_mesh_get_region_stat", [&] {
        require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL");
        require(value != nullptr, CBR_ERR_INVALID_ARGUMENT, "value is NULL");
        const int regions = mesh->recovery.done ? mesh->recovery.regions.count : 0;
        require(region >= 1 && region < regions, CBR_ERR_INVALID_ARGUMENT,
                "region " + std::to_string(region) + " is not a bounded region: " +
                    (regions > 1 ? "they are 1 to " + std::to_string(regions - 1)
                                 : std::string("there is none (call cbr_mesh_recover_faces first)")));
        const std::vector<cbr::refine::QualityTable>& tables = mesh->refine.region_quality;
        const auto r = static_cast<std::size_t>(region);
        const cbr::refine::QualityTable table = r < tables.size() ? tables[r] : cbr::refine::QualityTable{};
        if (!cbr::capi::table_two_stat(table, key, *value))
            throw ApiError{CBR_ERR_INVALID_ARGUMENT,
                           "statistic key " + std::to_string(key) +
                               " has no value per region (CBR_STAT_QUALITY_AVERAGE to CBR_STAT_DIHEDRAL_MAX, "
                               "and CBR_STAT_REFINE_TETS, do)"};
        return CBR_OK;
    });
}

}  // extern "C"

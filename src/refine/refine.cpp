#include "refine/refine.hpp"

#include "refine/field_points.hpp"
#include "refine/quality_flips.hpp"
#include "refine/refine_context.hpp"
#include "refine/sliver_removal.hpp"
#include "refine/smoothing.hpp"

namespace cbr::refine {

// Flips are tried on tetrahedra below this radius ratio (Table II counts
// q > 0.4 as good; flips up to 0.7 still raise the average markedly on
// graded meshes, whose surface layer dominates it).
constexpr double kFlipThreshold = 0.7;
// Tetrahedra below this radius ratio that flips and smoothing leave get a
// point with a chosen cavity (sliver_removal.hpp); Table II counts them bad.
constexpr double kSliverThreshold = 0.1;

RefineStats refine_mesh(mesh::TetMesh& m, const recover::ConstraintFaces& faces,
                        const std::vector<std::int32_t>& region_of_slot, const std::vector<mesh::VertexId>& steiner,
                        const RefineOptions& options, std::vector<double>* vertex_sizes) {
    RefineStats stats;
    RefineContext c(m, faces, region_of_slot, steiner, options);
    insert_field_points(c, stats);  // step (d)
    for (int pass = 0; pass < options.optimisation_passes; ++pass) {  // step (e)
        c.start_pass();
        const std::size_t flips = options.flips ? improve_by_flips(c, kFlipThreshold) : 0;
        const std::size_t moves = options.smoothing ? smooth_vertices(c) : 0;
        const std::size_t slivers = options.slivers ? remove_slivers(c, kSliverThreshold) : 0;
        stats.flips += flips;
        stats.smoothed += moves;
        stats.field_points += slivers;
        stats.sliver_points += slivers;
        if (flips == 0 && moves == 0 && slivers == 0) break;
    }
    for (mesh::TetId t = 0; t < m.slot_count(); ++t)
        if (c.in_domain(t) && !c.tet_within_size(t)) ++stats.unresolved_size;
    if (vertex_sizes) {
        vertex_sizes->resize(m.vertex_count());
        for (mesh::VertexId v = 0; v < m.vertex_count(); ++v) (*vertex_sizes)[v] = c.size.at(v);
    }
    return stats;
}

}  // namespace cbr::refine

#include "refine/refine.hpp"

#include <algorithm>
#include <vector>

#include "mesh/vertex_compaction.hpp"
#include "refine/angle_phase.hpp"
#include "refine/field_points.hpp"
#include "refine/quality_stats.hpp"
#include "refine/quality_flips.hpp"
#include "refine/refine_context.hpp"
#include "refine/sliver_removal.hpp"
#include "refine/smoothing.hpp"
#include "refine/steiner_relocation.hpp"
#include "refine/steiner_removal.hpp"
#include "refine/vertex_cones.hpp"

namespace cbr::refine {

// Flips are tried on tetrahedra below this radius ratio (Table II counts
// q > 0.4 as good; flips up to 0.7 still raise the average markedly on
// graded meshes, whose surface layer dominates it).
constexpr double kFlipThreshold = 0.7;
// Tetrahedra below this radius ratio that flips and smoothing leave get a
// point with a chosen cavity (sliver_removal.hpp); Table II counts them bad.
constexpr double kSliverThreshold = 0.1;
// Last, tetrahedra of four input points below this angle get a point
// judged by the angle (rescue_small_angles). Each such point roughly
// doubles the tetrahedra under q = 0.1 of its cavity (the flat patch caps
// them): on the 37 shared surfaces 198 more in all; taking tetrahedra
// with movable corners too, 649 more, for the same minima.
constexpr double kAngleRescueBelow = 1.0;
// Passes beyond options.optimisation_passes while the Steiner points still
// have bad tetrahedra: the first always (its cones from a vertex have not
// had their turn), the others while the last pass suppressed, relocated or
// coned one away. They are for the Steiner points, so they insert no
// sliver points: the sliver points of these late passes multiplied on
// thin walls (feeder body: 123,119 -> 153,983 tetrahedra in its last three
// passes, more of them under q = 0.1).
constexpr int kExtraSteinerPasses = 5;

namespace {

// The vertices whose tetrahedra the sliver points leave alone: the Steiner
// points and the points of their balls that can move (not input points).
std::vector<char> steiner_neighbourhoods(const RefineContext& c, const std::vector<mesh::VertexId>& steiner) {
    return grown_by_one_ring(c, steiner_flags(c.m, steiner), [&](mesh::VertexId v) { return c.is_movable(v); });
}

}  // namespace

RefineStats refine_mesh(mesh::TetMesh& m, const recover::ConstraintFaces& faces,
                        const std::vector<std::int32_t>& region_of_slot, std::vector<mesh::VertexId>& steiner,
                        const RefineOptions& options, std::vector<double>* vertex_sizes) {
    RefineStats stats;
    // Vertices from here on may be renumbered (Steiner and field points).
    const mesh::VertexId first_added = steiner.empty() ? 0 : *std::min_element(steiner.begin(), steiner.end());
    RefineContext c(m, faces, region_of_slot, steiner, options);
    insert_field_points(c, stats);  // step (d)
    // The passes below sweep every tetrahedron and walk around each one:
    // in the order insertion left them in memory, neighbours are scattered
    // (igea: the optimisation passes 7.9 -> 5.4 s with this, the flips
    // alone 4.5 -> 2.4 s; thingiverse-golf-ball's flips 1.05 -> 0.72 s).
    c.reorder_tets();
    bool dropped = false;  // a vertex left the mesh: the ids close up at the end
    // §6: Steiner points minimization, retried on the refined mesh.
    if (options.steiner_suppression) remove_bad_steiner_points(c, steiner, kSliverThreshold, stats, dropped);
    bool steiner_progress = false;
    for (int pass = 0; pass < options.optimisation_passes + kExtraSteinerPasses; ++pass) {  // step (e)
        const bool extra = pass >= options.optimisation_passes;  // kExtraSteinerPasses says when they run
        const bool first_extra = pass == options.optimisation_passes;
        if (extra && ((!first_extra && !steiner_progress) || bad_tets_at_steiner(c, steiner, kSliverThreshold) == 0))
            break;
        c.start_pass();
        const std::size_t flips = options.flips ? improve_by_flips(c, kFlipThreshold).total() : 0;
        const std::size_t moves = options.smoothing ? smooth_vertices(c) : 0;
        // §6: the Steiner points that still have a bad tetrahedron are
        // suppressed if their ball now allows it, else moved together
        // with their neighbourhood (steiner_relocation.hpp).
        const std::size_t suppressed =
            options.steiner_suppression ? remove_bad_steiner_points(c, steiner, kSliverThreshold, stats, dropped) : 0;
        const std::size_t relocated =
            options.steiner_relocation ? relocate_steiner_points(c, steiner, kSliverThreshold) : 0;
        // An extra pass: the cones from a vertex too (vertex_cones.hpp),
        // whose suppressions the next pass's flips and smoothing build on.
        std::size_t coned_away = 0;
        if (extra && options.vertex_cones) {
            const std::size_t before = stats.steiner_suppressed;
            improve_by_vertex_cones(c, steiner, kAngleRescueBelow, kSliverThreshold, stats, dropped);
            coned_away = stats.steiner_suppressed - before;
        }
        // Sliver points leave the tetrahedra at Steiner points, and at the
        // points next to them, to the steps above: points put there crowd
        // the Steiner point (the chain link's two kept 25 and 17 bad
        // tetrahedra, their nearest neighbours sliver points 0.15-0.6 away
        // where the edges are 1-4 long), and no later move or cone finds a
        // good ball among them. On the 37 shared surfaces Table II's last
        // row went 185 -> 138 with the Steiner points' own tetrahedra left
        // alone, -> 112 with their neighbours' too (under q = 0.1 18,174 ->
        // 18,125 -> 17,334); on 140 turned copies 197 -> 134 -> 81 (30,276
        // -> 30,444 -> 29,516; the first extra pass always running, above,
        // is part of the last step: without it 102 and 29,717, and the
        // chain link turned by seed 164 kept a 0.0012 deg tetrahedron).
        std::size_t slivers = 0;
        if (options.slivers && !extra) {
            const std::vector<char> near_steiner = steiner_neighbourhoods(c, steiner);
            slivers = remove_slivers(c, kSliverThreshold, stats, &near_steiner);
        }
        steiner_progress = suppressed > 0 || relocated > 0 || coned_away > 0;
        stats.steiner_relocated += relocated;
        stats.flips += flips;
        stats.smoothed += moves;
        stats.field_points += slivers;
        stats.sliver_points += slivers;
        if (flips == 0 && moves == 0 && !steiner_progress && slivers == 0) break;
    }
    improve_angles(c, options, kSliverThreshold, stats);  // the smallest dihedral angles
    if (options.slivers) {
        const std::size_t rescued = rescue_flat_slivers(c, kSliverThreshold, stats);
        const std::size_t for_angles =
            options.angle_rescue ? rescue_small_angles(c, kAngleRescueBelow, kSliverThreshold, stats) : 0;
        stats.field_points += rescued + for_angles;
        stats.sliver_points += rescued + for_angles;
        stats.angle_points += for_angles;
    }
    // Last, the cones from a vertex of the neighbourhood (vertex_cones.hpp)
    // for the smallest angles and the bad tetrahedra at Steiner points,
    // some of which the cones suppress; also in the extra passes above.
    // On the 37 shared surfaces (four meshes change): under q = 0.1 18,942
    // -> 18,802 tetrahedra, of them at a Steiner point 154 -> 57 (feeder
    // body 82 -> 57, octocat 45 -> 0, chain link 27 -> 0), average q
    // 0.7720 -> 0.7718 (the feeder body's extra passes add 9,700
    // tetrahedra), over the size bound 8,548 -> 8,400; two smallest angles
    // change: the feeder body's 2.2e-6 -> 3.3e-5 deg (TetGen 6.4e-4), the
    // chain link's 0.076 -> 0.073 (TetGen 0.0029). Measured: only here,
    // 112 at a Steiner point (82 -> 52, 45 -> 35, 27 -> 25); cones keeping
    // every vertex, 136; in every pass, 147, with 17,621 under q = 0.1
    // (the passes take other courses).
    if (options.vertex_cones)
        improve_by_vertex_cones(c, steiner, kAngleRescueBelow, kSliverThreshold, stats, dropped);
    for (mesh::TetId t = 0; t < m.slot_count(); ++t)
        if (c.in_domain(t) && !c.tet_within_size(t)) ++stats.unresolved_size;
    std::vector<double> sizes(m.vertex_count());
    for (mesh::VertexId v = 0; v < m.vertex_count(); ++v) sizes[v] = c.size.at(v);
    if (dropped) {
        // Suppressed points are in no tetrahedron: the ids after the input
        // points close up (Steiner points first, then field points).
        std::vector<mesh::VertexId> kept;
        mesh::compact_vertices_from(m, first_added, steiner, &kept);
        for (std::size_t i = 0; i < kept.size(); ++i) sizes[first_added + i] = sizes[kept[i]];
        sizes.resize(m.vertex_count());
    }
    if (vertex_sizes) vertex_sizes->swap(sizes);
    return stats;
}

}  // namespace cbr::refine

// Options and results of full mesh generation (Du & Wang 2004, §6 steps
// (d) and (e)): what cbr_mesh_refine's CBR_PARAM_* keys set and its
// CBR_STAT_* keys read.
#pragma once

#include <cstddef>

namespace cbr::refine {

struct RefineOptions {
    // Constant target edge length H; 0: none (the surface field alone).
    double target_size = 0;
    // Use the field derived from the surface (each surface vertex: mean
    // length of its input edges). With target_size > 0 the field is the
    // smaller of both; without the surface field, H alone.
    bool size_from_surface = true;
    // Grading g: the field is made g-Lipschitz over the mesh edges,
    // h(v) <= h(u) + g |uv| (a smooth field, §6: "the sizing field ...
    // should avoid large variation").
    double grading = 0.5;
    // Growth r: a point inserted at p takes, besides the value interpolated
    // there, up to min over the corners c of its tetrahedron of
    // h(c) + r |pc| (the larger of the two), so the field grows by r per
    // unit length away from the surface and the inside coarsens, as far
    // from the surface as the shape bound allows. 0: the surface field
    // interpolated, a solid meshed at its surface's resolution throughout.
    // Default 0.3: about 1.3x TetGen's tetrahedra (-pYq1.414) on the
    // benchmark surfaces at an average q above 0.77 (README, "Mesh
    // generation against TetGen").
    double growth = 0.3;
    // Radius-edge ratio bound B (circumradius / shortest edge) above which
    // a tetrahedron gets its circumcentre inserted (TetGen's -q bound).
    double quality_bound = 1.414;
    // Optimisation passes (each: quality flips, then smoothing); 0 = none.
    int optimisation_passes = 3;
    // Threads the field points, quality flips and smoothing sweeps may use
    // (CBR_PARAM_THREADS; the mesh is the same with any number:
    // vertex_halves.hpp).
    int threads = 1;
    // For tests: the vertex ids each half of the field points gets in its
    // first round (field_points.cpp; twice as many in each round after, up
    // to 16384).
    std::size_t field_point_round = 4096;
    // For tests: switch off one part of the optimisation.
    bool flips = true;
    bool smoothing = true;
    bool slivers = true;  // sliver removal (sliver_removal.hpp)
    bool steiner_suppression = true;  // steiner_removal.hpp
    bool steiner_relocation = true;   // steiner_relocation.hpp
    bool dihedral_flips = true;       // after the passes (quality_flips.hpp)
    bool sliver_face_bound = true;    // sliver removal's skip by a face's bound (same mesh either way)
    bool edge_removal_after_another = true;  // dihedral flips: an edge removal made possible by another first
    // Dihedral flips: chords over the size bound where the removed edge is
    // over it, none longer (quality_flips.cpp, Flipper::chord_limit2).
    bool dihedral_chords_up_to_removed_edge = true;
    bool dihedral_smoothing = true;   // after the dihedral flips (smoothing.hpp), then those flips again
    bool angle_rescue = true;         // then: rescue_small_angles (sliver_removal.hpp)
    bool vertex_cones = true;         // last, and in the extra passes: improve_by_vertex_cones (vertex_cones.hpp)
};

// Refinement accepts a tetrahedron when each of its non-surface edges uv is
// at most kEdgeFactor * (h(u) + h(v)) / 2 long (surface edges are input and
// never split). Flips and smoothing keep this bound, except that a flip for
// the smallest dihedral angle may replace an edge over it by chords no
// longer than that edge, and a cone from a vertex (vertex_cones.hpp) may
// make edges over it no longer than an edge of its cavity over it.
inline constexpr double kEdgeFactor = 1.5;
// An edge from a surface vertex u into the interior may always be as long as
// kSurfaceReach times the largest circumradius of the input triangles at u
// (refine_context.hpp, RefineContext::edge_size).
inline constexpr double kSurfaceReach = 1.25;

struct RefineStats {
    std::size_t field_points = 0;       // points inserted by refinement
    std::size_t size_fallbacks = 0;     // of which edge midpoints (circumcentre rejected)
    std::size_t rejected = 0;           // candidate points skipped (outside, encroaching, failed insertion)
    // Tetrahedra left over the size bound at the end: an over-long edge whose
    // circumcentre and midpoint were both refused (too close to the surface).
    std::size_t unresolved_size = 0;
    bool point_cap_hit = false;
    std::size_t cavity_tets = 0;        // tetrahedra removed by the insertions, in all (cost measure)
    std::size_t flips = 0;              // quality flips done (2-3 and edge removals)
    // Of the flips: pairs of edge removals, the first making the second
    // possible (two flips each).
    std::size_t removal_pairs = 0;
    std::size_t smoothed = 0;           // vertex moves accepted
    std::size_t dihedral_moves = 0;     // of them, moves for the smallest dihedral angle (smooth_for_dihedrals)
    std::size_t sliver_points = 0;      // of the field points: inserted by sliver removal
    std::size_t angle_points = 0;       // of those: for the smallest dihedral angle (rescue_small_angles)
    std::size_t sliver_cavities_skipped = 0;  // cavities sliver removal did not rate (a face's bound)
    std::size_t steiner_suppressed = 0; // Steiner points suppressed after refinement (steiner_removal.hpp)
    std::size_t steiner_relocated = 0;  // Steiner points moved with their neighbourhood (steiner_relocation.hpp)
    std::size_t vertex_cones = 0;       // cavities replaced by a vertex's cone (vertex_cones.hpp)
};

}  // namespace cbr::refine

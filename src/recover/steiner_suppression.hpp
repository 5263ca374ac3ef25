// Steiner point suppression (§6, "Steiner points minimization"): after the
// point splittings, try to take each Steiner point out of the mesh again by
// retetrahedralizing its ball without it. It is a heuristic: some points
// cannot go (Schönhardt's prism needs its Steiner point), and those stay.
//
// A suppressed vertex keeps its id and its coordinates in the coordinate
// array (vertex ids never change); it simply belongs to no tetrahedron any
// more. The caller keeps the list of the Steiner points that remain (see
// suppress_vertices) and must not count the suppressed ones as mesh
// vertices (check_mesh reports "vertex v is in no tetrahedron" for them).
//
// Guarantees, on success and on failure alike: no constraint face
// (TetMesh::is_constrained) is ever removed (replace_tets refuses), no edge
// that `protect` forbids is ever removed, every tetrahedron stays
// positively oriented (exact), and only the region of Ball(v) changes. On
// failure the region holds the original tetrahedra again (same vertex
// tuples; slot ids may differ if a flip was tried and undone).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "mesh/flips.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::recover {

enum class SuppressResult {
    kSuppressed,
    kBadInput,         // `start` is not a live tetrahedron containing v
    kHullVertex,       // v is on the hull (its ball has ghosts): not a Steiner point of the interior
    kOnConstraint,     // a constraint face contains v: removing v would remove it
    kProtectedEdge,    // an edge v-x is protected: every edge at v disappears with v
    kNoRetriangulation, // neither contraction nor flipping the ball down worked
    kRefused            // SuppressOptions::accept refused the new tetrahedra (the ball is back)
};

const char* to_string(SuppressResult r);

enum class SuppressMethod {
    kNone,
    kContraction,  // v contracted onto a link vertex (mechanism 1)
    kFlips,        // ball flipped down to four tetrahedra, then a 4-1 (mechanism 2)
};

struct SuppressOptions {
    bool contraction = true;  // mechanism 1
    bool flips = true;        // mechanism 2
    // Bound on the steps of mechanism 2 (edge removals and kept 2-3
    // flips); 0: automatic, 2 * |Ball(v)| + 8, more than a successful run
    // needs (each kept step lowers the degree of v or enables a step that
    // does). A smaller bound gives up earlier (and rolls back).
    std::size_t max_flip_steps = 0;
    // When set, the tetrahedra that fill the ball without v must pass it,
    // or the ball is put back and v stays (kRefused).
    std::function<bool(const mesh::TetMesh&, const std::vector<mesh::TetId>& created)> accept;
    // suppress_vertices: a pass skips a point whose ball is unchanged since
    // it failed in the pass before (it would fail again). Skipping changes
    // nothing but the time: false is there for the test that proves it.
    bool skip_unchanged_balls = true;
};

struct SuppressReport {
    SuppressResult result = SuppressResult::kBadInput;
    SuppressMethod method = SuppressMethod::kNone;
    std::size_t flips = 0;             // flips done (and kept, or undone on failure)
    std::size_t edge_removals = 0;     // edge removals of edges v-x (3-2 flips included), kept
    std::size_t link_flips = 0;        // 2-3 flips of faces at v, kept
    std::size_t flips_undone = 0;      // 2-3 flips undone at once (the look-ahead found no edge removal)
    double min_quality = 0;            // on success: worst tet_quality of the new tetrahedra
    // On success: the tetrahedra that now fill the old ball. On a failure
    // or refusal the mesh is as it was, bit for bit, and this is empty;
    // only when the caller holds the mesh's journal open are the original
    // tetrahedra put back by replace_tets and listed here (their slots may
    // differ).
    std::vector<mesh::TetId> created;
};

// Removes vertex v from m (Ball(v) retetrahedralized without it) if it
// can. `start` is a live tetrahedron containing v. Mechanisms, in order:
//  1. contraction of v onto a link vertex x: each ball tetrahedron
//     (v, a, b, c) not containing x becomes (x, a, b, c), those containing x
//     vanish. Every link vertex is tried; the one whose new tetrahedra have
//     the best minimum tet_quality wins.
//  2. flipping the ball down: edge removals (3-2 flips included) of edges
//     v-x, and 2-3 flips of faces inside the ball (which flip an edge of
//     the link) when they make an edge removal possible, until Ball(v) has
//     four tetrahedra, then the 4-1 flip (a contraction onto any of the
//     four link vertices). Contraction is retried after each step.
// Returns true when v was suppressed; `report` (optional) says how, or why
// not.
bool suppress_vertex(mesh::TetMesh& m, mesh::VertexId v, mesh::TetId start, const mesh::EdgeProtect& protect = {},
                     SuppressReport* report = nullptr, const SuppressOptions& options = {});

struct SuppressStats {
    std::size_t passes = 0;
    std::size_t suppressed = 0;      // by this call
    std::size_t by_contraction = 0;
    std::size_t by_flips = 0;
    // Why the remaining points stayed, as of the last pass.
    std::size_t kept_hull = 0;
    std::size_t kept_on_constraint = 0;
    std::size_t kept_protected = 0;
    std::size_t kept_no_retriangulation = 0;
    // Tries skipped: the point's ball was unchanged since its failure in
    // the pass before (SuppressOptions::skip_unchanged_balls).
    std::size_t skipped = 0;
};

// Tries every vertex of `steiner`, in order, in passes repeated while a
// pass suppresses something (suppressing one point can free its
// neighbour; a point whose ball did not change since it failed is not
// tried again, SuppressOptions::skip_unchanged_balls). Suppressed vertices
// are erased from `steiner` (the others keep their order); vertices found
// in no tetrahedron are erased too and not counted. Returns the number
// suppressed. Deterministic.
std::size_t suppress_vertices(mesh::TetMesh& m, std::vector<mesh::VertexId>& steiner,
                              const mesh::EdgeProtect& protect = {}, SuppressStats* stats = nullptr,
                              const SuppressOptions& options = {});

}  // namespace cbr::recover

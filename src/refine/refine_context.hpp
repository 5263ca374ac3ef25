// What the steps of full mesh generation share: the mesh, the region of
// every tetrahedron slot (kept up to date as tetrahedra are replaced:
// cavities and flips never cross a constraint face, so new tetrahedra
// inherit the region of the ones they replace), the sizing field, the
// input edges (never split) and the vertices that must not move.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/key_table.hpp"
#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"
#include "refine/quality_stats.hpp"
#include "refine/refine_options.hpp"
#include "refine/sizing_field.hpp"

namespace cbr::refine {

// For tests, the logs of the steps after the optimisation passes: one
// change, by the corners of the tetrahedra it replaced and of those it
// made (improve_dihedrals_by_flips, rescue_small_angles).
struct TetChange {
    std::vector<std::array<mesh::VertexId, 4>> replaced, made;
};

class RefineContext {
public:
    // `region`: per slot, from recover::classify_regions. `movable`: the
    // vertices optimisation may move (Steiner points of recovery); every
    // vertex added later is movable. `faces` must outlive the context.
    RefineContext(mesh::TetMesh& m, const recover::ConstraintFaces& faces, std::vector<std::int32_t> region,
                  const std::vector<mesh::VertexId>& movable, const RefineOptions& options);

    mesh::TetMesh& m;
    const RefineOptions options;
    SizingField size;
    // The quality flips' edges refused in a sweep (quality_flips.cpp),
    // emptied by each sweep: kept here so that its storage, millions of
    // edges on large meshes, is reused rather than grown again from empty
    // by every sweep (igea: that growth was 3% of the mesh generation).
    // One for a sweep of the whole mesh or of the border, one for each
    // half of improve_by_flips.
    mesh::KeyTable<bool> refused_edges;
    std::array<mesh::KeyTable<bool>, 2> half_refused_edges;

    // Region of slot t (0 outside, or for slots not assigned).
    std::int32_t region(mesh::TetId t) const { return t < region_.size() ? region_[t] : 0; }
    void set_region(mesh::TetId t, std::int32_t r);
    // A live finite tetrahedron of a bounded region (the part refined).
    bool in_domain(mesh::TetId t) const { return !m.is_free(t) && !m.is_ghost(t) && region(t) > 0; }

    bool is_surface_vertex(mesh::VertexId v) const { return v < surface_vertex_.size() && surface_vertex_[v]; }
    bool is_surface_edge(mesh::VertexId a, mesh::VertexId b) const;
    bool is_movable(mesh::VertexId v) const { return v >= movable_.size() || movable_[v]; }

    // The target length of edge uv: (h(u) + h(v)) / 2; for a non-input edge
    // joining two surface vertices, that value under the interior rule of
    // the field (capped by H, or H alone: SizingField::interior); for an
    // edge from a surface vertex u to an interior one, at least
    // kSurfaceReach / kEdgeFactor times the largest circumradius of the
    // input triangles at u.
    double edge_size(mesh::VertexId a, mesh::VertexId b) const;
    // The size bound (refine_options.hpp, kEdgeFactor): false when uv is a
    // non-surface edge longer than kEdgeFactor * edge_size(u, v).
    bool edge_within_size(mesh::VertexId a, mesh::VertexId b) const;
    // The size bound with an allowance: uv within the bound, or at most
    // sqrt(limit2) long. A step that replaces or moves edges may keep one
    // over the bound if it does not grow past what was there: the chords
    // of the flips for the angle, the cones from a vertex, the smoothing.
    bool edge_within_size(mesh::VertexId a, mesh::VertexId b, double limit2) const;
    // Every edge of t within the size bound.
    bool tet_within_size(mesh::TetId t) const;

    // Change tracking for the optimisation passes: each tetrahedron slot
    // remembers the pass in which it was last created (set_region) or
    // reshaped (touch: a corner moved). A pass need not look again at what
    // did not change since the pass before it: its attempt there failed
    // and would fail again.
    void start_pass() { ++pass_; }
    void touch(mesh::TetId t);
    // Room for the region and stamp of every slot of m, so that touch()
    // and set_region() do not grow the arrays: before threads reshape or
    // replace tetrahedra at once.
    void reserve_slots() {
        if (stamp_.size() < m.slot_count()) stamp_.resize(m.slot_count(), 0);
        if (region_.size() < m.slot_count()) region_.resize(m.slot_count(), -1);
    }
    // The current pass, and whether t was created or reshaped in that pass
    // or after it.
    std::uint32_t pass() const { return pass_; }
    bool changed_since(mesh::TetId t, std::uint32_t pass) const { return (t < stamp_.size() ? stamp_[t] : 0) >= pass; }
    // t or a tetrahedron across one of its faces changed in pass `pass` or
    // after it.
    bool changed_near_since(mesh::TetId t, std::uint32_t pass) const;
    // Created or reshaped during the previous pass or this one (every slot
    // before the second pass), and the same for t or a face neighbour.
    bool changed(mesh::TetId t) const { return changed_since(t, previous_pass()); }
    bool changed_near(mesh::TetId t) const { return changed_near_since(t, previous_pass()); }

    // Renumbers the tetrahedra of m along the Hilbert curve through their
    // centroids (delaunay::hilbert_order; the regions and change stamps
    // follow, free slots are dropped): the sweeps and walks after it read
    // neighbouring tetrahedra from nearby memory.
    void reorder_tets();

    // Registers a point appended to m (value of the sizing field there).
    void add_vertex(double h) { size.add(h); }

    const std::vector<std::int32_t>& regions() const { return region_; }

private:
    std::uint32_t previous_pass() const { return pass_ > 0 ? pass_ - 1 : 0; }

    const recover::ConstraintFaces& faces_;  // outlives the context (is_surface_edge)
    std::vector<std::int32_t> region_;
    std::vector<std::uint32_t> stamp_;  // per slot: the pass that last created or reshaped it
    std::uint32_t pass_ = 0;            // 0 during refinement, then 1, 2, ... per optimisation pass
    std::vector<char> surface_vertex_;
    std::vector<double> reach_;  // per surface vertex: largest circumradius of its input triangles
    std::vector<char> movable_;
};

// The flags (one per vertex) grown by one ring of vertices: every corner
// of a tetrahedron of the bounded regions with a corner flagged in `flags`
// is flagged in the copy returned, if `may_flag(corner)`.
template <class MayFlag>
std::vector<char> grown_by_one_ring(const RefineContext& c, const std::vector<char>& flags, MayFlag may_flag) {
    std::vector<char> grown = flags;
    for (mesh::TetId t = 0; t < c.m.slot_count(); ++t) {
        if (!c.in_domain(t) || !has_flagged_corner(c.m, t, flags)) continue;
        for (int i = 0; i < 4; ++i)
            if (may_flag(c.m.vertex(t, i))) grown[c.m.vertex(t, i)] = 1;
    }
    return grown;
}

}  // namespace cbr::refine

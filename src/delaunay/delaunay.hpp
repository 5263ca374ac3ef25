// The Delaunay tetrahedralization of a growing point set, updated one batch
// of points at a time. Degenerate configurations are resolved by the
// symbolic perturbation of geom::insphere_sos, so the result is unique: it
// depends on the point set only, not on batches or order.
//
// Two numberings: callers' ("external") ids follow the order of insertion
// calls; the mesh's ("internal") vertex ids follow the order in which the
// points are inserted, BRIO rounds along a Hilbert curve, so that the
// vertices of nearby tetrahedra are nearby in memory (about 20% faster on a
// million points than coordinates in caller order). external_id() and
// internal_id() convert.
#pragma once

#include <cstdint>
#include <vector>

#include "delaunay/kernel.hpp"
#include "geom/predicates.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::delaunay {

// Result of a batch insertion.
struct InsertOutcome {
    bool ok = true;
    // When !ok: two points with identical coordinates (external ids,
    // first < second).
    mesh::VertexId duplicate_first = 0, duplicate_second = 0;
};

class Delaunay {
public:
    Delaunay();
    Delaunay(const Delaunay&) = delete;
    Delaunay& operator=(const Delaunay&) = delete;

    // Appends `count` points (3 doubles each, finite and in the predicates'
    // range: the caller checks) and updates the tetrahedralization. On
    // duplicate points, or when an exception (std::bad_alloc, ...) leaves
    // this function, the previous state is restored exactly (see
    // rebuild) and the outcome names the duplicates.
    InsertOutcome insert_points(const double* xyz, std::size_t count);

    // The mesh, in internal vertex ids.
    const mesh::TetMesh& mesh() const { return mesh_; }
    // For the steps that modify it (boundary recovery); rebuild() brings
    // back the Delaunay tetrahedralization.
    mesh::TetMesh& mesh_for_update() { return mesh_; }
    // Rebuilds the state as it was after the successful batches: the
    // algorithm is deterministic, so replaying them gives bit-identical
    // arrays (same tetrahedra, same order).
    void rebuild();
    // Forgets the last successful batch (its points leave both numberings)
    // and rebuilds: the state before that batch, bit for bit.
    void drop_last_batch();
    // Points that a later step appended to the mesh (Steiner and field
    // points, TetMesh::add_points) join both numberings with external id ==
    // internal id, i.e. after the caller's points in the order they were
    // added. rebuild() drops them again (back to the last batch). Added
    // points that a later step dropped again (ids compacted, so the mesh
    // has fewer points than both numberings) leave the numberings too.
    void adopt_added_vertices();
    mesh::VertexId external_id(mesh::VertexId internal) const { return external_of_[internal]; }
    mesh::VertexId internal_id(mesh::VertexId external) const { return internal_of_[external]; }
    const geom::PredicateCounters& counters() const { return counters_; }
    // Finite (non-ghost) tetrahedra.
    std::size_t finite_tet_count() const;

private:
    // Appends the points in BRIO order and records both numberings.
    void store_batch(const double* xyz, std::size_t count);
    void discard_vertices_from(std::size_t count);
    // Inserts vertices [first, end) (internal ids) as one batch.
    InsertOutcome insert_batch(mesh::VertexId first, std::size_t end);
    // Before the first tetrahedron exists: finds four affinely independent
    // points among [0, n), builds the first tetrahedron and returns true
    // with the other points in `rest`. False when there is no such
    // quadruple (then duplicates among them, if any, are in `outcome`).
    bool start_triangulation(std::size_t n, std::vector<mesh::VertexId>& rest, InsertOutcome& outcome);

    mesh::TetMesh mesh_;
    geom::PredicateCounters counters_;
    Kernel kernel_;
    std::vector<std::size_t> batch_ends_;  // vertex count after each successful batch
    std::vector<mesh::VertexId> external_of_, internal_of_;
};

}  // namespace cbr::delaunay

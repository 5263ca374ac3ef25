// §5.2 Conforming face/edge recovery: points added on the missing edges and
// in the interiors of the missing faces until every input triangle is a
// union of mesh faces (sub-faces) whose vertices are its corners and the
// added points (recorded in SurfacePoints). Splitting (point_splitting)
// then moves every added point off the surface.
//
// Insertion kernel (§5.1 protected insertion with cavity correction): the
// initial cavity of a point is the smallest one that removes the crossing
// it is put on — the two tetrahedra of a crossed face, or the shell of a
// crossed edge — rather than the Delaunay cavity of the paper: then every
// insertion removes exactly one crossing and touches no other edge, so no
// recovered part of any constraint (sub-edge, sub-face) is lost and the
// process ends after as many insertions as there were crossings. The
// cavity correction never crosses a constraint face or a sub-face.
//
// Rounded points on the edges of a thin face can make a flat tetrahedron
// whose four vertices are all points of that face; both its upper and its
// lower face then count as sub-faces, and the face is no disk. Such
// tetrahedra are removed by edge removal before the disk check; an edge
// that skips points of a chain (a shortcut: along the chain in exact
// geometry) may go even where it borders another triangle's "sub-face".
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/protected_insertion.hpp"
#include "recover/segment_walk.hpp"
#include "recover/surface_points.hpp"

namespace cbr::recover {

class ConformingRecovery {
public:
    ConformingRecovery(mesh::TetMesh& m, SurfacePoints& points);

    // Edges of input triangle `face` as chains of mesh edges, then its
    // interior as sub-faces. False (with why()) when a step fails.
    bool recover_face(std::size_t face);
    const std::string& why() const { return why_; }
    // Incident tetrahedron per vertex, kept up to date (all vertices).
    std::vector<mesh::TetId>& incident() { return incident_; }

private:
    using Position = std::array<double, 3>;
    bool recover_edge(mesh::VertexId a, mesh::VertexId b);
    bool crossing_point(const Crossing& c, mesh::VertexId q, mesh::VertexId b, Position& xyz,
                        std::vector<mesh::TetId>& cavity);
    // A point to try and its initial cavity.
    struct Candidate {
        Position xyz;
        std::vector<mesh::TetId> cavity;
    };
    std::vector<Candidate> other_crossing_points(const Crossing& c, mesh::VertexId q, mesh::VertexId b,
                                                const std::vector<mesh::TetId>& cavity);
    mesh::VertexId insert_joined(const Position& xyz, const std::vector<mesh::TetId>& cavity, mesh::VertexId q);
    void undo_last_insertion(mesh::VertexId p);
    bool recover_interior(std::size_t face);
    mesh::VertexId insert_on_crossing(const double* xyz, mesh::VertexId u, mesh::VertexId w, const double* A,
                                      const double* B, const double* C, const std::vector<mesh::TetId>& shell);
    // Every flat tetrahedron of the face; `removed`: how many there were.
    bool remove_flat_tets(std::size_t face, std::size_t& removed);
    mesh::TetId find_flat_tet(std::size_t face);
    bool is_flat(mesh::TetId t, std::size_t face) const;
    bool remove_flat_tet(std::size_t face, mesh::TetId t);
    bool disk_is_complete(std::size_t face);
    // Inserts a point at xyz with `cavity` as initial cavity (with
    // `keep_cavity`, the correction keeps its finite tetrahedra); returns
    // its id or kGhostVertex (why_ set).
    mesh::VertexId insert(const double* xyz, std::vector<mesh::TetId> cavity, bool keep_cavity);
    bool edge_exists(mesh::VertexId a, mesh::VertexId b) const;
    void note_created(const std::vector<mesh::TetId>& created);
    bool fail(std::string why) {
        why_ = std::move(why);
        return false;
    }

    mesh::TetMesh& m_;
    SurfacePoints& points_;
    std::vector<mesh::TetId> incident_;
    ProtectedInserter inserter_;  // keeps its scratch storage across insertions
    std::string why_;
};

}  // namespace cbr::recover

// The surface while recovery works on it (§5.2-5.4): the input triangles,
// the points conforming recovery adds on their edges and interiors, and
// which input triangles each surface point belongs to.
//
// An *added point* lies (approximately: it is a rounded intersection
// point) on an input edge or in an input triangle and is temporary:
// splitting turns it into Steiner points off the surface. A face's
// *points* are its three corners, the added points on its edges and those
// in its interior; a mesh face whose three vertices are points of one
// input triangle is a *sub-face* of it (the conforming recovery
// represents the triangle as a union of them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"

namespace cbr::recover {

class SurfacePoints {
public:
    static constexpr std::size_t npos = ConstraintFaces::npos;

    SurfacePoints(const ConstraintFaces& faces, std::size_t vertex_count);

    // Records p as a point added on input edge ab (a, b corners of a face).
    void add_edge_point(mesh::VertexId p, mesh::VertexId a, mesh::VertexId b);
    // Records p as a point added in the interior of input triangle `face`.
    void add_face_point(mesh::VertexId p, std::size_t face);
    // p is no longer a surface point (it was split off the surface).
    void remove(mesh::VertexId p);

    bool is_added(mesh::VertexId v) const { return find_added(v) != nullptr; }
    // Vertices from this id on were made by the recovery (added points,
    // then Steiner points).
    mesh::VertexId first_new_vertex() const { return first_new_; }
    // For an added point: true when it lies on an edge (then *a, *b are the
    // edge's ends), false when inside a triangle (then *face is it).
    bool on_edge(mesh::VertexId v, mesh::VertexId* a, mesh::VertexId* b, std::size_t* face) const;
    // The input triangles v belongs to (as a corner, or as an added point).
    void faces_of(mesh::VertexId v, std::vector<std::size_t>& out) const;
    bool belongs_to(mesh::VertexId v, std::size_t face) const;
    // An input triangle all of x, y, z belong to, or npos.
    std::size_t common_face(mesh::VertexId x, mesh::VertexId y, mesh::VertexId z) const;
    bool is_subface(mesh::VertexId x, mesh::VertexId y, mesh::VertexId z) const {
        return common_face(x, y, z) != npos;
    }
    // x, y, z all lie on one input edge (its ends, or points added on it):
    // collinear in exact geometry, whatever their rounded coordinates say.
    bool on_one_edge(mesh::VertexId x, mesh::VertexId y, mesh::VertexId z) const;
    // Input triangles with edge ab.
    std::vector<std::uint32_t> faces_of_edge(mesh::VertexId a, mesh::VertexId b) const;

    // The chain of mesh edges that represents input edge ab once it is
    // recovered in a conforming manner (a first, b last); empty if not yet.
    std::vector<mesh::VertexId> chain(mesh::VertexId a, mesh::VertexId b) const;
    void set_chain(mesh::VertexId a, mesh::VertexId b, std::vector<mesh::VertexId> chain);
    // xy is a link of the chain of an input edge (two consecutive points
    // of it; an input edge recovered as it was is a chain of one link).
    bool is_chain_link(mesh::VertexId x, mesh::VertexId y) const;
    // Removes added point p from the chain it belongs to.
    void remove_from_chain(mesh::VertexId p);

    // Added points in the order they were added (removed ones included).
    const std::vector<mesh::VertexId>& added_in_order() const { return order_; }
    const ConstraintFaces& faces() const { return faces_; }

private:
    struct Added {
        mesh::VertexId a = 0, b = 0;  // edge points: the input edge
        std::size_t face = npos;      // face points: the triangle; npos for edge points
        bool live = false;            // an added point not yet split off the surface
    };
    // The record of added point v, or nullptr (an input point, a Steiner
    // point, or an added point already split).
    const Added* find_added(mesh::VertexId v) const {
        if (v < first_new_ || v - first_new_ >= added_.size()) return nullptr;
        const Added& x = added_[v - first_new_];
        return x.live ? &x : nullptr;
    }
    Added& record(mesh::VertexId p);

    const ConstraintFaces& faces_;
    std::vector<std::uint32_t> corner_first_, corner_faces_;  // vertex -> triangles (CSR)
    // Per vertex id from first_new_ on (ids are dense: the points added and
    // the Steiner points come after the input's), looked up by the hot
    // sub-face tests without hashing.
    mesh::VertexId first_new_;
    std::vector<Added> added_;
    std::unordered_map<std::uint64_t, std::vector<mesh::VertexId>> chains_;  // stored from min id to max id
    std::vector<mesh::VertexId> order_;
    mutable std::vector<std::size_t> candidates_;  // common_face's scratch: no allocation per test
};

}  // namespace cbr::recover

// The boundary of a cavity (a set of tetrahedra to be replaced by a star or
// a cone over it): its faces as the cavity's tetrahedra see them, and the
// vertices on them. Shared by the retetrahedralizations that grow a
// cavity and then check which of its vertices would be left inside
// (refine/steiner_relocation.cpp, refine/vertex_cones.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/slot_marks.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::mesh {

struct CavityFace {
    // kFaceVertices order of the cavity tetrahedron it bounds: the cavity
    // is on its positive side (orient3d(v, p) > 0 for p inside).
    std::array<VertexId, 3> v;
    bool constrained;  // a constraint face (always on the boundary)
};

// Calls face(f) for each face f of the tetrahedra `cavity` that is a
// constraint face or lies against a tetrahedron outside it (`inside(t)`:
// whether t is in it), in the order of `cavity` and of the faces.
template <typename Inside, typename Face>
void each_cavity_face(const TetMesh& m, const std::vector<TetId>& cavity, Inside inside, Face face) {
    for (TetId t : cavity) {
        const VertexId* w = m.vertices(t);
        for (int f = 0; f < 4; ++f) {
            const bool constrained = m.is_constrained(t, f);
            if (!constrained && inside(facet_tet(m.neighbor(t, f)))) continue;
            const int* k = kFaceVertices[f];
            face(CavityFace{{w[k[0]], w[k[1]], w[k[2]]}, constrained});
        }
    }
}

// The boundary faces of `cavity` (each_cavity_face) into `faces`; their
// vertices, sorted and distinct, into `vertices`.
template <typename Inside>
void cavity_boundary(const TetMesh& m, const std::vector<TetId>& cavity, Inside inside,
                     std::vector<CavityFace>& faces, std::vector<VertexId>& vertices) {
    faces.clear();
    vertices.clear();
    each_cavity_face(m, cavity, inside, [&](const CavityFace& f) {
        faces.push_back(f);
        vertices.insert(vertices.end(), f.v.begin(), f.v.end());
    });
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
}

// The same faces; their vertices get `mark` in `vertex_marks` (a new
// round, for m's vertices), for membership tests where the list is not
// needed (no sort: a cavity is grown and tested again and again).
template <typename Inside>
void cavity_boundary(const TetMesh& m, const std::vector<TetId>& cavity, Inside inside,
                     std::vector<CavityFace>& faces, SlotMarks& vertex_marks, std::uint8_t mark) {
    faces.clear();
    vertex_marks.new_round(m.vertex_count());
    each_cavity_face(m, cavity, inside, [&](const CavityFace& f) {
        faces.push_back(f);
        for (VertexId v : f.v) vertex_marks.set(v, mark);
    });
}

}  // namespace cbr::mesh

// The boundary of a cavity (a set of tetrahedra to be replaced by a star or
// a cone over it): its faces as the cavity's tetrahedra see them, and the
// vertices on them. Shared by the retetrahedralizations that grow a
// cavity and then check which of its vertices would be left inside
// (refine/steiner_relocation.cpp, refine/vertex_cones.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::mesh {

struct CavityFace {
    // kFaceVertices order of the cavity tetrahedron it bounds: the cavity
    // is on its positive side (orient3d(v, p) > 0 for p inside).
    std::array<VertexId, 3> v;
    bool constrained;  // a constraint face (always on the boundary)
};

// The faces of the tetrahedra `cavity` that are constraint faces or lie
// against a tetrahedron outside it (`inside(t)`: whether t is in it),
// into `faces`; their vertices, sorted and distinct, into `vertices`.
template <typename Inside>
void cavity_boundary(const TetMesh& m, const std::vector<TetId>& cavity, Inside inside,
                     std::vector<CavityFace>& faces, std::vector<VertexId>& vertices) {
    faces.clear();
    vertices.clear();
    for (TetId t : cavity) {
        const VertexId* w = m.vertices(t);
        for (int f = 0; f < 4; ++f) {
            const bool constrained = m.is_constrained(t, f);
            if (!constrained && inside(facet_tet(m.neighbor(t, f)))) continue;
            const int* k = kFaceVertices[f];
            faces.push_back({{w[k[0]], w[k[1]], w[k[2]]}, constrained});
            for (int i = 0; i < 3; ++i) vertices.push_back(w[k[i]]);
        }
    }
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
}

}  // namespace cbr::mesh

// Helpers of the mesh-level tests (flips, protected insertion, Steiner
// points): building a mesh from explicit tetrahedra, face keys, brute-force
// point location.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "delaunay/delaunay.hpp"
#include "geom/predicates.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::test {

using Tet = std::array<mesh::VertexId, 4>;
using Key3 = std::array<mesh::VertexId, 3>;

// Face f of t as a sorted vertex triple.
inline Key3 face_key(const mesh::TetMesh& m, mesh::TetId t, int f) {
    Key3 k = {m.vertex(t, mesh::kFaceVertices[f][0]), m.vertex(t, mesh::kFaceVertices[f][1]),
              m.vertex(t, mesh::kFaceVertices[f][2])};
    std::sort(k.begin(), k.end());
    return k;
}

inline bool live_finite(const mesh::TetMesh& m, mesh::TetId t) { return !m.is_free(t) && !m.is_ghost(t); }

// All the mesh's arrays, slot by slot (vertices, neighbour links, flags),
// the free list's length and the coordinates: equal only for the same
// mesh bit for bit, slots included.
struct SlotSnapshot {
    std::vector<std::array<std::uint32_t, 9>> rows;
    std::size_t free_count = 0;
    mesh::LargeArray<double> coords;
    explicit SlotSnapshot(const mesh::TetMesh& m) : free_count(m.free_count()), coords(m.coordinates()) {
        for (mesh::TetId t = 0; t < m.slot_count(); ++t)
            rows.push_back({m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3), m.neighbor(t, 0),
                            m.neighbor(t, 1), m.neighbor(t, 2), m.neighbor(t, 3), m.flags(t)});
    }
    bool operator==(const SlotSnapshot& o) const {
        return rows == o.rows && free_count == o.free_count && coords == o.coords;
    }
};

inline mesh::TetMesh delaunay_mesh(const std::vector<double>& xyz) {
    delaunay::Delaunay d;
    REQUIRE(d.insert_points(xyz.data(), xyz.size() / 3).ok);
    return d.mesh();
}

// The mesh of the given positively oriented tetrahedra; ghosts close the
// faces used once, and tetrahedra are linked through shared faces.
inline mesh::TetMesh build_mesh(const std::vector<double>& xyz, const std::vector<Tet>& tets) {
    using mesh::kFaceVertices;
    mesh::TetMesh m;
    m.add_points(xyz.data(), xyz.size() / 3);
    std::map<Key3, std::vector<mesh::FacetRef>> faces;
    for (const Tet& v : tets) {
        const mesh::TetId t = m.allocate_tet();
        m.set_vertices(t, v[0], v[1], v[2], v[3]);
        for (int f = 0; f < 4; ++f) faces[face_key(m, t, f)].push_back(mesh::make_facet(t, f));
    }
    std::vector<std::pair<mesh::TetId, int>> hull;
    for (const auto& [key, refs] : faces)
        if (refs.size() == 1) hull.push_back({mesh::facet_tet(refs[0]), mesh::facet_face(refs[0])});
    for (const auto& [t, f] : hull) {
        const mesh::TetId g = m.allocate_tet();  // (a, c, b, oo): oo on the outer side
        m.set_vertices(g, m.vertex(t, kFaceVertices[f][0]), m.vertex(t, kFaceVertices[f][2]),
                       m.vertex(t, kFaceVertices[f][1]), mesh::kGhostVertex);
        for (int h = 0; h < 4; ++h) faces[face_key(m, g, h)].push_back(mesh::make_facet(g, h));
    }
    for (const auto& [key, refs] : faces) {
        REQUIRE(refs.size() == 2);
        m.link(refs[0], refs[1]);
    }
    return m;
}

// Brute force: a live finite tetrahedron containing q (closed), or kNoTet.
inline mesh::TetId locate(const mesh::TetMesh& m, const double* q) {
    for (mesh::TetId t = 0; t < m.slot_count(); ++t) {
        if (!live_finite(m, t)) continue;
        bool inside = true;
        for (int f = 0; f < 4 && inside; ++f) {
            const int* k = mesh::kFaceVertices[f];
            inside = geom::orient3d(m.point(m.vertex(t, k[0])), m.point(m.vertex(t, k[1])),
                                    m.point(m.vertex(t, k[2])), q) >= 0;
        }
        if (inside) return t;
    }
    return mesh::kNoTet;
}

}  // namespace cbr::test

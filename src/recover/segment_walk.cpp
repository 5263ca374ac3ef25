#include "recover/segment_walk.hpp"

#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"

namespace cbr::recover {

using mesh::kFaceVertices;
using mesh::TetId;
using mesh::VertexId;

Crossing first_crossing(const mesh::TetMesh& m, VertexId u, TetId start, VertexId w) {
    Crossing c;
    const double* pw = m.point(w);
    int ui = -1, zeros = 0, zero_face[2] = {-1, -1};
    // The first tetrahedron of u's ball (in mesh::ball's order) that holds
    // w in its cone at u; the rest of the ball is not walked.
    const TetId t = mesh::first_in_ball(m, u, start, [&](TetId x) {
        if (m.is_ghost(x)) return false;
        ui = mesh::vertex_index(m, x, u);
        zeros = 0;
        const VertexId* v = m.vertices(x);
        for (int g = 0; g < 4; ++g) {
            if (g == ui) continue;
            const int s = geom::orient3d(m.point(v[kFaceVertices[g][0]]), m.point(v[kFaceVertices[g][1]]),
                                         m.point(v[kFaceVertices[g][2]]), pw);
            if (s < 0) return false;
            if (s == 0 && zeros < 2) zero_face[zeros++] = g;
        }
        return true;
    });
    if (t == mesh::kNoTet) return c;
    const VertexId* v = m.vertices(t);
    c.tet = t;
    if (zeros == 0) {
        c.kind = Crossing::kFace;
        c.face = ui;
    } else if (zeros == 1) {
        // Along face zero_face[0]: through its edge opposite u.
        c.kind = Crossing::kEdge;
        int n = 0;
        for (int h = 0; h < 4; ++h)
            if (h != ui && h != zero_face[0]) (n++ == 0 ? c.x : c.y) = v[h];
    } else {
        // Along two faces: through the vertex they share besides u.
        c.kind = Crossing::kVertex;
        for (int h = 0; h < 4; ++h)
            if (h != ui && h != zero_face[0] && h != zero_face[1]) c.x = v[h];
    }
    return c;
}

geom::SegTriKind classify_segment_face(const mesh::TetMesh& m, mesh::VertexId u, mesh::VertexId w, mesh::VertexId a,
                                       mesh::VertexId b, mesh::VertexId c) {
    const bool at_u = a == u || b == u || c == u;
    const bool at_w = a == w || b == w || c == w;
    // At one end only (at both, uw is an edge of the triangle): the line
    // meets the plane at that vertex unless the other end is in the plane.
    if (at_u != at_w && geom::orient3d(m.point(a), m.point(b), m.point(c), m.point(at_u ? w : u)) != 0)
        return geom::SegTriKind::EndpointVertex;
    return geom::classify_segment_triangle(m.point(u), m.point(w), m.point(a), m.point(b), m.point(c)).kind;
}

}  // namespace cbr::recover

// Walking a segment through the mesh (recovery.md, "Exact primitives"):
// what the open segment u -> w meets first when it leaves vertex u. The
// workhorse of flip recovery (remove what the segment crosses) and of
// conforming recovery (insert a point where it crosses).
#pragma once

#include "geom/intersect.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::recover {

struct Crossing {
    enum Kind { kNone, kFace, kEdge, kVertex } kind = kNone;
    mesh::TetId tet = mesh::kNoTet;  // the tetrahedron of u's ball the segment enters
    int face = -1;                   // kFace: the face of `tet` crossed (opposite u)
    mesh::VertexId x = 0, y = 0;     // kEdge: the edge crossed; kVertex: x is the vertex
};

// The finite tetrahedron of u's ball whose cone at u holds w (the first in
// mesh::ball's order when w is on the boundary of several), and what the
// segment crosses there: the opposite face, one of its edges, or a vertex
// (when the segment runs through it). `start` is a tetrahedron containing
// u. kNone when u's ball has no such tetrahedron (w outside the hull seen
// from u).
Crossing first_crossing(const mesh::TetMesh& m, mesh::VertexId u, mesh::TetId start, mesh::VertexId w);

// geom::classify_segment_triangle's kind for segment uw and triangle abc,
// all mesh vertices. A triangle with u or w as a vertex (most faces met
// when walking from u's ball) meets the segment only there, an
// EndpointVertex, whenever the other end is off its plane: one
// orientation then decides what the general test takes five for (two
// of them at exactly zero).
geom::SegTriKind classify_segment_face(const mesh::TetMesh& m, mesh::VertexId u, mesh::VertexId w, mesh::VertexId a,
                                       mesh::VertexId b, mesh::VertexId c);

}  // namespace cbr::recover

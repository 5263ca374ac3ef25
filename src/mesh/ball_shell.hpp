// Ball of a vertex and shell of an edge (§5.1: Ball(P) is the set of
// tetrahedra incident to P; the shell of an edge is the ring of
// tetrahedra around it), found by walking neighbours from one incident
// tetrahedron. kGhostVertex is a vertex like the others: its ball is the
// set of ghosts, the shell of a hull edge contains two ghosts.
#pragma once

#include <functional>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::mesh {

// Position of v in t (0..3), or -1.
int vertex_index(const TetMesh& m, TetId t, VertexId v);

// t is a live tetrahedron with u and v among its vertices (u != v): the
// start that shell() needs.
bool holds_edge(const TetMesh& m, TetId t, VertexId u, VertexId v);

// Every tetrahedron incident to v, `start` first, then in breadth-first
// order. False (and `out` empty) when `start` is not a live tetrahedron
// containing v.
bool ball(const TetMesh& m, VertexId v, TetId start, std::vector<TetId>& out);

// The shell of edge uv in rotation order: tets[i] has the vertices u, v,
// ring[i], ring[i+1 mod n], and (u, v, ring[i], ring[i+1]) is an even
// permutation of its stored order, i.e. positively oriented when finite
// (the ring turns counter-clockwise seen from v). tets[0] is the start.
struct Shell {
    std::vector<TetId> tets;
    std::vector<VertexId> ring;
    std::size_t size() const { return tets.size(); }
    bool has_ghost() const;
};
// False (and `out` empty) when `start` is not a live tetrahedron containing
// u and v (u != v), or when the shell has more than `max_size` tetrahedra
// (the walk stops there: callers that refuse large shells skip the rest).
bool shell(const TetMesh& m, VertexId u, VertexId v, TetId start, Shell& out,
           std::size_t max_size = static_cast<std::size_t>(-1));

// A tetrahedron containing edge uv, found in the ball of u (`start`
// contains u); kNoTet when uv is not an edge.
TetId find_edge_tet(const TetMesh& m, VertexId u, TetId start, VertexId v);

// The first tetrahedron of v's ball, in ball()'s order, that `accept`
// takes; the walk goes no further than needed to find it. kNoTet when
// none does, or when `start` is not a live tetrahedron containing v.
TetId first_in_ball(const TetMesh& m, VertexId v, TetId start, const std::function<bool(TetId)>& accept);

// One live tetrahedron per vertex (a finite one when the vertex has any;
// kNoTet for a vertex in no tetrahedron), in one pass over the mesh.
std::vector<TetId> incident_tets(const TetMesh& m);

// The balls of all vertices at once: each vertex's live tetrahedra (as
// ball() gives them, but by ascending slot), from two sweeps over the
// slots. For a pass that visits every vertex's ball while the
// tetrahedra stay as they are (smoothing moves points only): a walk per
// vertex reads the mesh in scattered order, and was a quarter of igea's
// smoothing. Stale once a tetrahedron is created or removed.
class VertexBalls {
public:
    explicit VertexBalls(const TetMesh& m);
    // The ball of v into `out`; empty for a vertex in no tetrahedron.
    void get(VertexId v, std::vector<TetId>& out) const;
    bool empty(VertexId v) const { return offsets_[v] == offsets_[v + 1]; }

private:
    std::vector<std::size_t> offsets_;  // v's tetrahedra: tets_[offsets_[v] .. offsets_[v + 1])
    std::vector<TetId> tets_;
};

}  // namespace cbr::mesh

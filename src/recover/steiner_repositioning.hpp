// Steiner point repositioning (§6): move each Steiner point that
// suppression left in the mesh to a better place inside its ball — the
// paper's "optimal positions" (AFT placement or smoothing). Here: a few
// rounds of a 1-D search toward candidate points (the centroid of the
// link, the average of the link faces' ideal apexes, the ideal apex of the
// worst tetrahedron's link face), accepting a move only when the minimum
// tet_quality of the ball strictly increases.
//
// Exactness: a candidate point is rounded to doubles first; everything
// below is then decided by orient3d on the stored doubles. A move is
// accepted only when every ball tetrahedron is strictly positively
// oriented with the new point, so the cones from the point to the link
// faces still tile the ball's region and the point is strictly inside it;
// the point can therefore reach no input triangle except those on the
// ball's boundary (every input triangle is a mesh face after recovery, and
// a face meets the interior of no tetrahedron). It is nevertheless checked
// exactly (point-in-triangle by orient3d) against every input triangle
// whose bounding box meets the ball's (so the guarantee holds even for a
// triangle that is not yet a face) and every constraint face of the link.
// Cost: one pass over the input triangles per point moved.
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"

namespace cbr::recover {

struct RepositionOptions {
    int rounds = 8;     // search rounds per point and pass
    int halvings = 24;  // step lengths 1, 1/2, ..., 2^-halvings toward each candidate
    int passes = 3;     // passes over all the points, repeated while one moves (a neighbour may free another)
    // Every input triangle is a face of the mesh already (the end of
    // recovery): a point kept strictly inside its ball can then meet none
    // but those on the ball's boundary, so the others are not searched.
    bool all_faces_present = false;
};

struct RepositionStats {
    std::size_t points = 0;   // Steiner points looked at
    std::size_t moved = 0;    // moved at least once
    std::size_t skipped = 0;  // hull vertex, on a constraint face, or not in the mesh
    // Worst tet_quality over the balls of all the points, before the first
    // and after the last move (+inf when no ball was looked at). Moves
    // never lower it: each one only changes its own ball, whose minimum it
    // raises.
    double min_quality_before = 0;
    double min_quality_after = 0;
};

// Moves vertex v (a Steiner point: no constraint face contains it) within
// its ball; `start` is a live tetrahedron containing v. Returns true when
// v moved. `before` / `after` (optional): the ball's minimum quality.
// `faces`: the input triangles (mesh vertex ids), for the exact check that
// v lands on none of those bounding its ball. A hull vertex (ghosts in its
// ball) or a vertex of a constraint face is not moved.
bool reposition_vertex(mesh::TetMesh& m, mesh::VertexId v, mesh::TetId start, const ConstraintFaces& faces,
                       const RepositionOptions& options = {}, double* before = nullptr, double* after = nullptr);

// reposition_vertex for every vertex of `steiner`, in order, in up to
// `options.passes` passes while some point moves. Vertex ids never change;
// vertices in no tetrahedron are skipped.
RepositionStats reposition_steiner_points(mesh::TetMesh& m, const std::vector<mesh::VertexId>& steiner,
                                          const ConstraintFaces& faces, const RepositionOptions& options = {});

}  // namespace cbr::recover

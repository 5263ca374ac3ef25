// Steiner point merging (§6, "Steiner points minimization", beyond the
// paper's suppression): two Steiner points joined by an edge are replaced
// by one when the union of their balls is star-shaped from a single point
// — the union is then coned from that point. Suppression removes a point
// whose ball can be rebuilt from one of its link vertices; points that
// splitting left in clusters (dimples, crowded faces) often cannot go
// alone but can go in pairs.
//
// Guarantees: no constraint face is removed (the union's interior faces
// must carry none; replace_tets checks again), no vertex but the absorbed
// Steiner point leaves the mesh, every new tetrahedron is positively
// oriented (exact), and the kept point lies strictly inside the union, so
// on no input triangle.
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::recover {

// Merges adjacent pairs of `steiner` (in order, each point with its first
// neighbour that works), in passes while one merges. The absorbed points
// are erased from `steiner` and belong to no tetrahedron afterwards; the
// kept one moves to the best position found (largest minimum tet_quality
// among the candidates). Returns the number of points removed.
// Deterministic.
std::size_t merge_steiner_pairs(mesh::TetMesh& m, std::vector<mesh::VertexId>& steiner);

}  // namespace cbr::recover

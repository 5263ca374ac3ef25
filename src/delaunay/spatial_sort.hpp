// Insertion order for incremental Delaunay: a biased randomized insertion
// order (BRIO, Amenta-Choi-Rote 2003) whose rounds are each sorted along a
// 3D Hilbert curve. Randomness keeps the expected cost optimal; the curve
// keeps consecutive points close, so each point-location walk is short.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::delaunay {

// Position of (x, y, z) along a 3D Hilbert curve of 2^bits cells per axis;
// x, y, z < 2^bits, bits <= 21.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits);

// The indices 0 .. n-1 of the n points `xyz` (x, y, z each) in their order
// along the Hilbert curve over their bounding box, ties by index: points
// near each other in space are near each other in the order (the surface
// check builds its box tree on the triangles' box centres so).
std::vector<std::size_t> hilbert_order(const double* xyz, std::size_t n);

// Reorders ids into BRIO rounds, each Hilbert-sorted. Deterministic for a
// given seed.
void brio_sort(const double* coords, std::vector<mesh::VertexId>& ids, std::uint64_t seed);

}  // namespace cbr::delaunay

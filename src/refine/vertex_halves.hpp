// Two halves of the vertices a smoothing sweep may move, so that two
// threads (CBR_PARAM_THREADS) can move them at once and the mesh is the
// same whatever the number of threads.
//
// The vertices are split at the median of their coordinate along the
// longest side of their bounding box. An inner vertex of a half has no
// vertex of the other half in its link: two inner vertices of different
// halves are not joined by an edge, so they share no tetrahedron, and
// neither reads the position the other one writes (a move rates the
// ball of the vertex: its tetrahedra and the positions of its link). The
// inner vertices of the two halves may thus be moved at the same time,
// each half in increasing id order, then the border vertices (the rest)
// in increasing id order. That order does not depend on the number of
// threads; with one thread the halves simply run one after the other.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::refine {

struct VertexHalves {
    std::array<std::vector<mesh::VertexId>, 2> inner;  // increasing ids
    std::vector<mesh::VertexId> border;                // increasing ids
};

// Per vertex of m: 0 or 1 for the half of `vertices` it is in (split at
// the median of their coordinate along the longest side of their bounding
// box, ties by id), kNoHalf for the other vertices.
inline constexpr std::uint8_t kNoHalf = 2;
// `plane`, when given: the axis and the median coordinate (that of the
// first vertex of half 1), for labelling points added later.
struct MedianPlane {
    int axis = 0;
    double at = 0;
    std::uint8_t half_of(const double* p) const { return p[axis] < at ? 0 : 1; }
};
std::vector<std::uint8_t> median_halves(const mesh::TetMesh& m, const std::vector<mesh::VertexId>& vertices,
                                        MedianPlane* plane = nullptr);

// The half of tetrahedron t when the vertices carry half labels: the label
// of its four corners when they all have the same, else (and for a ghost)
// kNoHalf. The one rule by which the quality flips (quality_flips.cpp) and
// the field points (field_points.cpp) give tetrahedra to halves.
inline std::uint8_t common_half(const std::vector<std::uint8_t>& label, const mesh::TetMesh& m, mesh::TetId t) {
    const mesh::VertexId* v = m.vertices(t);
    if (v[3] == mesh::kGhostVertex) return kNoHalf;
    const std::uint8_t h = label[v[0]];
    return label[v[1]] == h && label[v[2]] == h && label[v[3]] == h ? h : kNoHalf;
}

// A half's claim on the tetrahedra (the field points in halves,
// field_points.cpp): those whose common_half is `half` (0 or 1).
struct HalfClaim {
    const std::vector<std::uint8_t>* label = nullptr;  // per vertex id
    std::uint8_t half = 0;
    bool owns(const mesh::TetMesh& m, mesh::TetId t) const { return common_half(*label, m, t) == half; }
};

// Splits `moving` (increasing ids: the vertices a sweep may move; no other
// vertex moves during it) as above.
VertexHalves split_in_halves(const mesh::TetMesh& m, const std::vector<mesh::VertexId>& moving);

}  // namespace cbr::refine

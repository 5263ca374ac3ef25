// Plain data exchanged between the file readers/writers and the `cbr`
// command. No invariants are enforced by the types themselves: the readers
// produce consistent meshes, and the writers validate what they are given.
//
// All indices are 0-based. Flat arrays: point i is xyz[3i..3i+2], triangle t
// is tris[3t..3t+2], tetrahedron k is tets[4k..4k+3].
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cbr::io {

// A triangulated surface as read from a file.
struct SurfaceMesh {
    std::vector<double> xyz;          // 3 per point
    std::vector<std::int64_t> tris;   // 3 per triangle, 0-based point ids
    std::vector<std::int32_t> labels; // 1 per triangle (0 when the format has none)

    std::size_t num_points() const { return xyz.size() / 3; }
    std::size_t num_triangles() const { return tris.size() / 3; }
};

// A tetrahedral mesh to be written (or read back from a Medit file).
// Tetrahedra are positively oriented in cbr.h's sense (det[b-a, c-a, d-a] >
// 0), which is also the convention of Medit, VTK, Gmsh and TetGen; the
// writers pass vertex order through unchanged.
struct VolumeMesh {
    std::vector<double> xyz;              // 3 per point
    std::vector<std::int64_t> tets;       // 4 per tetrahedron
    std::vector<std::int32_t> tet_regions;// 1 per tetrahedron
    std::vector<std::int64_t> tris;       // 3 per boundary/input triangle
    std::vector<std::int32_t> tri_labels; // 1 per triangle
    std::vector<std::uint8_t> is_steiner; // 1 per point (0/1), or empty: none
    std::vector<double> tet_quality;      // 1 per tetrahedron, or empty: none

    std::size_t num_points() const { return xyz.size() / 3; }
    std::size_t num_tets() const { return tets.size() / 4; }
    std::size_t num_triangles() const { return tris.size() / 3; }
};

}  // namespace cbr::io

// What `cbr check` computes itself from a triangle list, beside libcbr's
// exact checks (cbr_mesh_check_faces): duplicate points (exact equality),
// non-manifold vertices, orientation, connected components, bounding box,
// signed volume. Plain combinatorics on the arrays read by cbr::io; ids
// 0-based.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cbr::cli {

using IdPair = std::array<std::int64_t, 2>;

// Points with bit-for-bit equal coordinates (0.0 and -0.0 are equal).
// Points with a NaN or infinite coordinate are left alone (libcbr rejects
// them when they are inserted).
struct DuplicatePoints {
    std::vector<std::int64_t> first_of;  // per point: the smallest id at the same place
    std::int64_t count = 0;              // points that repeat an earlier one
    std::vector<IdPair> listed;          // the first few (first, repeat), by repeat id
};
DuplicatePoints find_duplicate_points(const std::vector<double>& xyz, std::size_t max_listed);

// Triangles with ids out of range or repeated are ignored here (libcbr
// reports them).
struct Topology {
    std::int64_t used_points = 0;         // points used by a triangle
    std::int64_t open_edges = 0;          // edges of one triangle
    std::int64_t misoriented_edges = 0;   // edges whose triangles disagree on orientation
    std::vector<IdPair> misoriented_listed;
    std::int64_t nonmanifold_vertices = 0;  // triangle fan not one umbrella
    std::vector<std::int64_t> nonmanifold_listed;
    std::int64_t components = 0;  // triangles connected through shared vertices
    // Shells: triangles connected across edges of exactly two triangles (two
    // tetrahedra sharing an edge are two shells). A closed shell (each edge
    // used an even number of times by its triangles) encloses a volume:
    // positive for outward normals. Volumes are in floating point (a
    // report, not a decision).
    std::int64_t shells = 0, open_shells = 0, outward_shells = 0, inward_shells = 0;
    double signed_volume = 0;  // of the whole surface

    bool closed() const { return open_edges == 0; }
    bool consistent() const { return misoriented_edges == 0; }
};
Topology analyse_topology(const std::vector<double>& xyz, const std::vector<std::int64_t>& tris,
                          std::size_t max_listed);

struct BoundingBox {
    std::array<double, 3> lo{}, hi{};
    bool empty = true;
};
BoundingBox bounding_box(const std::vector<double>& xyz);

}  // namespace cbr::cli

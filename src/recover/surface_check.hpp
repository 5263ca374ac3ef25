// Validation of an input surface before boundary recovery.
//
// Errors (recovery must refuse the input): a vertex id out of range, a
// triangle repeating a vertex id, a zero-area triangle (exactly collinear
// vertices), the same triangle twice (same vertex set, any order), and two
// triangles meeting other than in a shared vertex or a shared edge (exact,
// geom::triangles_meet_illegally on the candidate pairs of a bounding-box
// tree: O(n log n) plus the pairs whose boxes touch).
//
// Information (legal for recovery, reported for the caller's benefit): open
// edges (used by one triangle: the surface does not close there) and
// non-manifold edges (used by more than two triangles: several regions
// meeting along an edge). An odd count is not called open: two cubes sharing
// a face have 3 triangles on each edge of that face and enclose both cubes.
//
// Not checked here: coordinates (finite, within the predicates' range) and
// duplicate points; the caller does that. Two distinct ids with identical
// coordinates are distinct vertices, so triangles that meet only there
// meet illegally.
//
// Pure function of its input: deterministic, no global state.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cbr::recover {

enum class DefectKind : std::uint8_t {
    // Errors.
    IdOutOfRange,       // tri[0]; vert = its three ids; value = point count
    RepeatedId,         // tri[0]; vert = its three ids
    ZeroArea,           // tri[0]; vert = its three ids
    DuplicateTriangle,  // tri[0] < tri[1], same vertex set; vert = tri[1]'s ids
    Intersection,       // tri[0] < tri[1]; vert = the vertex ids they share
    // Information.
    OpenEdge,         // vert[0] < vert[1]; tri[0] = the triangle on it; value = 1
    NonManifoldEdge,  // vert[0] < vert[1]; tri[0] = first triangle on it;
                      // value = number of triangles on it (> 2)
};
inline constexpr std::size_t kDefectKindCount = 7;

// True for the kinds that make the input unusable.
bool is_error(DefectKind kind);

struct Defect {
    DefectKind kind = DefectKind::IdOutOfRange;
    std::array<std::int64_t, 2> tri = {-1, -1};     // triangle indices, -1 unused
    std::array<std::int64_t, 3> vert = {-1, -1, -1};  // vertex ids, -1 unused
    std::int64_t value = -1;                          // per kind, see DefectKind
};

struct SurfaceCheckOptions {
    // At most this many defects of each kind are listed (the first ones in
    // the deterministic order below); the counts are always complete.
    std::size_t max_listed_per_kind = 20;
    bool report_edges = true;  // compute the OpenEdge / NonManifoldEdge info
    // Per triangle, when given: nonzero where the caller knows the triangle
    // to be a face of a valid tetrahedralization of the points (every
    // tetrahedron positively oriented, exactly; cbr_mesh_check_faces: its
    // mesh). Two faces of one such tetrahedralization meet only in a shared
    // vertex or edge, so the pairs of two of them are not tested; every
    // pair with another triangle is, and the result is the same. (igea:
    // 1,349 of its 268,686 triangles are not faces of the Delaunay mesh.)
    const std::vector<char>* known_faces = nullptr;
};

struct SurfaceCheckResult {
    // Ordered by kind, then by triangle indices (edges: by vertex ids).
    std::vector<Defect> defects;
    // Total number of defects of each kind, listed or not.
    std::array<std::int64_t, kDefectKindCount> counts{};

    std::int64_t count(DefectKind kind) const { return counts[static_cast<std::size_t>(kind)]; }
    std::int64_t error_count() const;
    bool ok() const { return error_count() == 0; }
};

// Checks `triangle_count` triangles (3 vertex ids each, 0-based, in `tris`)
// over `point_count` points (3 coordinates each, in `xyz`).
SurfaceCheckResult check_surface(const double* xyz, std::int64_t point_count,
                                 const std::int64_t* tris, std::int64_t triangle_count,
                                 const SurfaceCheckOptions& options = {});

// One-line message, e.g. "triangles 12 and 873 intersect (not in a shared
// vertex or edge)". Indices and ids are printed plus `index_base` (1 for a
// caller that numbers from 1).
std::string describe(const Defect& defect, int index_base = 0);

// Short summary of the errors: "no defect" or e.g. "3 errors: 2 intersecting
// triangle pairs, 1 zero-area triangle; first: <describe(first error)>".
std::string summarize(const SurfaceCheckResult& result, int index_base = 0);

}  // namespace cbr::recover

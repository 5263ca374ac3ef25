// How near a valid surface comes to being degenerate, for `cbr check`:
// the two closest points and the flattest triangle. Neither is an error,
// but recovery adds no point on the surface, so where two points are a few
// ulps apart, or a triangle is a few ulps thick, the points that conforming
// recovery needs between them may not exist in double precision, and
// recovery can fail there (CBR_ERR_RECOVERY_FAILED) on a surface that the
// exact checks accept.
#pragma once

#include <cbr/cbr.h>

#include <cstdint>
#include <vector>

namespace cbr::cli {

// Below this share of its scale (the bounding box's diagonal for a
// distance, the longest edge for a triangle's height) the report adds a
// note: about 500 ulps of a coordinate near the box's size.
constexpr double kNearlyDegenerate = 1e-13;

struct ClosestPoints {
    bool found = false;  // false with fewer than 4 points, or all coplanar
    double distance = 0;
    std::int64_t a = 0, b = 0;  // point ids (as in xyz), a < b
};

// The two closest distinct points of xyz: the ends of the shortest edge of
// their Delaunay tetrahedralization in `mesh` (a point's nearest neighbour
// is always a Delaunay neighbour), which holds exactly the points of xyz,
// in the same order, before any recovery.
ClosestPoints closest_points(const cbr_mesh* mesh, const std::vector<double>& xyz);

struct FlattestTriangle {
    bool found = false;  // false when no triangle has three distinct ids in range
    double height_ratio = 0;  // smallest height / longest edge (0: collinear in double)
    std::int64_t triangle = 0;
};

// The triangle of `tris` (3 ids each, into xyz) whose smallest height is
// the smallest share of its longest edge; triangles with an id out of
// range or repeated are left out (errors of their own).
FlattestTriangle flattest_triangle(const std::vector<double>& xyz, const std::vector<std::int64_t>& tris);

// Both, and the scale the closest points are measured against.
struct SurfaceMargins {
    ClosestPoints closest;
    FlattestTriangle flattest;
    double diagonal = 0;  // of the points' bounding box
    // Either under kNearlyDegenerate of its scale.
    bool nearly_degenerate() const;
};

// closest_points and flattest_triangle of the surface xyz, tris, whose
// points `mesh` holds as closest_points says.
SurfaceMargins measure_margins(const cbr_mesh* mesh, const std::vector<double>& xyz,
                               const std::vector<std::int64_t>& tris);

}  // namespace cbr::cli

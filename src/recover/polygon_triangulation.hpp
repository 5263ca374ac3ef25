// Triangulation of a planar polygon without new vertices: the polygon
// P1 ... Pn that the cap and ball transformations (§5.1, Definitions 5.7
// and 5.8) triangulate when an added point leaves the surface.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "geom/orient2d.hpp"

namespace cbr::recover {

// Triangulates the simple polygon `loop` (vertex coordinates, in order;
// nearly planar) seen through projection `pr`, in which the loop turns
// with sign `turn` (+1 counter-clockwise, -1 clockwise). Among the
// triangulations whose triangles are all strictly of sign `turn`, contain
// no other polygon vertex and whose diagonals cross no polygon edge (all
// decided exactly), returns one that maximizes the smallest triangle
// quality (dynamic programming over the polygon; O(n^3), chords
// memoized, so the 200-gons of a fanned CAD cap take milliseconds, not
// seconds). Above kMaxOptimalPolygon vertices, the greedy ear clipping
// below instead. Triangles are index triples (i < j < k), which follow the
// loop's turn. Empty when there is none (e.g. the projection folds the
// polygon). `flat`, when given, names triangles to leave out whatever
// their sign: corners known to be collinear in exact geometry, whose
// computed sign is only rounding.
using FlatTriangle = std::function<bool(int, int, int)>;
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<const double*>& loop, geom::Projection pr,
                                                    int turn, const FlatTriangle& flat = {});

// Whether chord ij of `loop` (0 <= i, j < loop.size(), not a polygon
// edge) crosses no polygon edge at a point interior to both and holds no
// polygon vertex in its interior, seen through `pr` (exact): the sides a
// triangle of triangulate_polygon may have.
bool chord_is_clear(const std::vector<const double*>& loop, geom::Projection pr, int i, int j);

// Polygons up to this size get the optimal triangulation; the feeder
// body's conforming recovery made fans of up to 922 vertices, whose
// O(n^3) search took most of a 40-second recovery.
inline constexpr int kMaxOptimalPolygon = 64;

// The same triangles' conditions, met by ear clipping in O(n^2): the ear
// (corner with both neighbours) of best quality is cut first, where an
// ear is a strictly convex corner (sign `turn`), not `flat`, whose closed
// triangle holds no other vertex of the polygon left; in a simple polygon
// its new side is then a diagonal. The polygon must be simple (the fan of
// an added point is: star-shaped around the point); empty when no ear is
// left before the end (only `flat` can do that to a simple polygon).
std::vector<std::array<int, 3>> triangulate_polygon_by_ears(const std::vector<const double*>& loop,
                                                            geom::Projection pr, int turn,
                                                            const FlatTriangle& flat = {});

}  // namespace cbr::recover

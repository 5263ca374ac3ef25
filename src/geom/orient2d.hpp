// Exact 2D orientation of points projected onto a coordinate plane.
//
// The projection keeps coordinates (u, v) of each point. With
// a' = (a_u, a_v, 0) and so on, orient3d(a', b', c', (0, 0, 1)) is
// det[[b'-a'], [c'-a'], [-a_u, -a_v, 1]] = (b-a)_u (c-a)_v - (b-a)_v (c-a)_u,
// the 2D orientation of the projected points (counter-clockwise positive).
// Only copies of input coordinates and the constants 0 and 1 are involved,
// so the result is as exact as orient3d.
#pragma once

#include "geom/predicates.hpp"

namespace cbr::geom {

struct Projection {
    int u;
    int v;
};

inline int orient2d(Projection pr, const double* a, const double* b, const double* c) {
    const double pa[3] = {a[pr.u], a[pr.v], 0.0};
    const double pb[3] = {b[pr.u], b[pr.v], 0.0};
    const double pc[3] = {c[pr.u], c[pr.v], 0.0};
    const double up[3] = {0.0, 0.0, 1.0};
    return orient3d(pa, pb, pc, up);
}

// The projection that drops the coordinate in which a plane with normal n
// is steepest: the projected plane is then as little squashed as possible.
inline Projection projection_along(const double n[3]) {
    const double ax = n[0] < 0 ? -n[0] : n[0], ay = n[1] < 0 ? -n[1] : n[1], az = n[2] < 0 ? -n[2] : n[2];
    if (az >= ax && az >= ay) return {0, 1};
    if (ax >= ay) return {1, 2};
    return {2, 0};
}

}  // namespace cbr::geom

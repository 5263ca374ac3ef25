// Exact point-in-triangle test in 3D, reduced to orient3d: p lies in the
// closed triangle abc when it is coplanar with abc and, for each edge, on
// the same side as the opposite vertex of the plane through that edge and
// an apex d off the plane. The apex is a copy of a with one coordinate
// doubled (or set to 1 when 0): d - a is then an exact axis vector, so
// orient3d(a, b, c, d) is a nonzero multiple of one component of the exact
// normal, and one of the three axes always works for a non-degenerate
// triangle. No constructed point is trusted beyond what orient3d says.
#pragma once

#include "geom/predicates.hpp"

namespace cbr::geom {

// True when p lies in the closed triangle abc (exact). False for a
// degenerate (collinear) triangle.
inline bool point_in_triangle(const double* p, const double* a, const double* b, const double* c) {
    if (orient3d(a, b, c, p) != 0) return false;
    for (int k = 0; k < 3; ++k) {
        double d[3] = {a[0], a[1], a[2]};
        d[k] = a[k] == 0 ? 1.0 : 2 * a[k];
        if (orient3d(a, b, c, d) == 0) continue;  // this axis is parallel to the plane
        const double* v[3] = {a, b, c};
        for (int e = 0; e < 3; ++e) {
            const double* s = v[e];
            const double* t = v[(e + 1) % 3];
            const double* opposite = v[(e + 2) % 3];
            if (orient3d(s, t, d, p) * orient3d(s, t, d, opposite) < 0) return false;
        }
        return true;
    }
    return false;
}

}  // namespace cbr::geom

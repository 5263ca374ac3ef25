// A rounded point of a segment that is neither of its ends: conforming
// recovery (§5.2) puts its intersection points where a missing edge meets
// a mesh face or edge, and a crossing within rounding of an end would be
// that end again once rounded.
#pragma once

#include <limits>

#include "geom/predicates.hpp"

namespace cbr::geom {

// p + s (q - p) for s in (0, 1), rounded, and moved along pq by steps
// doubling from an ulp until it is neither p nor q (p != q). True when it
// had to be moved.
inline bool segment_point_off_ends(const double* p, const double* q, double s, double out[3]) {
    const auto at = [&](double t) {
        for (int k = 0; k < 3; ++k) out[k] = p[k] + t * (q[k] - p[k]);
    };
    at(s);
    const bool moved = same_point(out, p) || same_point(out, q);
    for (double step = std::numeric_limits<double>::epsilon(); same_point(out, p) && s + step < 0.5; step *= 2)
        at(s + step);
    for (double step = std::numeric_limits<double>::epsilon(); same_point(out, q) && s - step > 0.5; step *= 2)
        at(s - step);
    return moved;
}

}  // namespace cbr::geom

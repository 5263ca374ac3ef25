// Dot and cross products of 3-vectors given as raw coordinate arrays, for
// the constructions (not the predicates) of recovery: rounded, like any
// arithmetic on doubles.
#pragma once

namespace cbr::geom {

inline double dot(const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

inline double squared_distance(const double* p, const double* q) {
    const double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
    return dot(d, d);
}

// w = u x v (w must not alias u or v).
inline void cross(const double* u, const double* v, double* w) {
    w[0] = u[1] * v[2] - u[2] * v[1];
    w[1] = u[2] * v[0] - u[0] * v[2];
    w[2] = u[0] * v[1] - u[1] * v[0];
}

}  // namespace cbr::geom

// "Flat to within rounding": the cone of face abc and apex p is flatter
// than a sine of kFlatCone, estimated in floating point. The exact sign of
// such a cone is decided by rounding errors of constructed points (an
// intersection point meant to lie on a plane lands an ulp off it), so the
// recovery treats it like a coplanar one (§5.1 cavity correction: take in
// the tetrahedron beyond). A topological choice only: every tetrahedron is
// still tested exactly before it is kept.
#pragma once

#include <cmath>

namespace cbr::geom {

// Far above rounding (1e-16), far below any shape a mesh should keep.
inline constexpr double kFlatCone = 1e-12;

inline bool flat_cone(const double* a, const double* b, const double* c, const double* p) {
    double x[3], y[3], z[3];
    for (int i = 0; i < 3; ++i) {
        x[i] = b[i] - a[i];
        y[i] = c[i] - a[i];
        z[i] = p[i] - a[i];
    }
    const double n[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
    const double det = n[0] * z[0] + n[1] * z[1] + n[2] * z[2];
    const double scale =
        std::sqrt((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * (z[0] * z[0] + z[1] * z[1] + z[2] * z[2]));
    return std::fabs(det) <= kFlatCone * scale;
}

}  // namespace cbr::geom

// Squared Euclidean distance from a point to a closed triangle in 3D
// (rounded: the closest point by Voronoi regions of the vertices, edges and
// interior, as in Ericson, "Real-Time Collision Detection", 5.1.5). For
// clearances only; exact questions (is the point on the triangle) go to
// point_in_triangle.hpp.
#pragma once

namespace cbr::geom {

inline double distance2_to_triangle(const double* p, const double* a, const double* b, const double* c) {
    const auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int k = 0; k < 3; ++k) {
        ab[k] = b[k] - a[k];
        ac[k] = c[k] - a[k];
        ap[k] = p[k] - a[k];
        bp[k] = p[k] - b[k];
        cp[k] = p[k] - c[k];
    }
    // Squared distance from p to a + u ab + v ac.
    const auto at = [&](double u, double v) {
        double r[3];
        for (int k = 0; k < 3; ++k) r[k] = ap[k] - u * ab[k] - v * ac[k];
        return dot(r, r);
    };
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return at(0, 0);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return at(1, 0);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return at(d1 / (d1 - d3), 0);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return at(0, 1);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return at(0, d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return at(1 - w, w);
    }
    const double den = 1 / (va + vb + vc);
    return at(vb * den, vc * den);
}

}  // namespace cbr::geom

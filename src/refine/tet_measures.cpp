#include "refine/tet_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geom/predicates.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace cbr::refine {
namespace {

using V = std::array<double, 3>;

V sub(const double* p, const double* q) { return {p[0] - q[0], p[1] - q[1], p[2] - q[2]}; }
V sub(const V& p, const V& q) { return {p[0] - q[0], p[1] - q[1], p[2] - q[2]}; }
double dot(const V& p, const V& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }
double len(const V& p) { return std::sqrt(dot(p, p)); }
V cross(const V& p, const V& q) { return {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]}; }
V mul(const V& p, double s) { return {p[0] * s, p[1] * s, p[2] * s}; }

constexpr double kPi = 3.14159265358979323846;

#if defined(__SSE2__)
// Two vectors at once, one per lane of SSE2 registers: the operations of
// sub, dot, len and cross in their order (no fused multiply-add:
// -ffp-contract=off), so each lane rounds exactly as the scalar code does.
struct Lanes3 {
    __m128d x, y, z;
};
inline Lanes3 sub2(const Lanes3& p, const Lanes3& q) {
    return {_mm_sub_pd(p.x, q.x), _mm_sub_pd(p.y, q.y), _mm_sub_pd(p.z, q.z)};
}
inline __m128d dot2(const Lanes3& p, const Lanes3& q) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(p.x, q.x), _mm_mul_pd(p.y, q.y)), _mm_mul_pd(p.z, q.z));
}
inline __m128d len2(const Lanes3& p) { return _mm_sqrt_pd(dot2(p, p)); }
inline Lanes3 cross2(const Lanes3& p, const Lanes3& q) {
    return {_mm_sub_pd(_mm_mul_pd(p.y, q.z), _mm_mul_pd(p.z, q.y)),
            _mm_sub_pd(_mm_mul_pd(p.z, q.x), _mm_mul_pd(p.x, q.z)),
            _mm_sub_pd(_mm_mul_pd(p.x, q.y), _mm_mul_pd(p.y, q.x))};
}
inline Lanes3 corner2(const double* first, const double* second) {
    return {_mm_set_pd(second[0], first[0]), _mm_set_pd(second[1], first[1]), _mm_set_pd(second[2], first[2])};
}
#endif

// Edges from a, scaled so that the longest of the six edges is 1 (q and the
// angles do not change; every product stays near 1). False if degenerate.
bool unit_edges(const double* a, const double* b, const double* c, const double* d, V& u, V& v, V& w) {
    u = sub(b, a);
    v = sub(c, a);
    w = sub(d, a);
    const double longest = std::max({dot(u, u), dot(v, v), dot(w, w), dot(sub(v, u), sub(v, u)),
                                     dot(sub(w, u), sub(w, u)), dot(sub(w, v), sub(w, v))});
    if (!(longest > 0) || !std::isfinite(longest)) return false;
    const double s = 1 / std::sqrt(longest);
    u = mul(u, s);
    v = mul(v, s);
    w = mul(w, s);
    return true;
}

// q from the edges u, v, w at one corner; false (q not set) when the
// products, of six lengths, leave the range where double keeps its full
// precision.
[[gnu::always_inline]] inline bool radius_ratio_of(const V& u, const V& v, const V& w, double& q) {
    const V vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
    const double det = dot(u, vw);  // 6 x signed volume
    // r_in = |det| / (2 S), S = sum of face areas; r_circ = |N| / (2 |det|).
    const double area2 = len(uv) + len(wu) + len(vw) + len(cross(sub(v, u), sub(w, u)));  // 2 S
    const double uu = dot(u, u), vv = dot(v, v), ww = dot(w, w);
    const V n = {uu * vw[0] + vv * wu[0] + ww * uv[0], uu * vw[1] + vv * wu[1] + ww * uv[1],
                 uu * vw[2] + vv * wu[2] + ww * uv[2]};
    const double denominator = area2 * len(n);
    if (!(denominator >= 1e-280 && denominator <= 1e280)) return false;
    q = 6 * det * det / denominator;  // 3 * (|det| / 2S) / (|N| / 2|det|)
    return true;
}

}  // namespace

double six_volume(const double* a, const double* b, const double* c, const double* d) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double s[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return std::fabs(u[0] * (s[1] * w[2] - s[2] * w[1]) - u[1] * (s[0] * w[2] - s[2] * w[0]) +
                     u[2] * (s[0] * w[1] - s[1] * w[0]));
}

// q is scale-free: the raw edges first (the common case, no scaling
// needed), the edges scaled to a unit longest edge when a product leaves
// the range of double.
double radius_ratio(const double* a, const double* b, const double* c, const double* d) {
    double q = 0;
    if (!radius_ratio_of(sub(b, a), sub(c, a), sub(d, a), q)) {
        V u, v, w;
        if (!unit_edges(a, b, c, d, u, v, w) || !radius_ratio_of(u, v, w, q)) return 0;
    }
    if (!std::isfinite(q)) return 0;
    return std::clamp(q, 0.0, 1.0);
}

// radius_ratio_of in the lanes of Lanes3 (or, without SSE2, radius_ratio
// twice).
void radius_ratio_pair(const double* const first[4], const double* const second[4], double out[2]) {
#if defined(__SSE2__)
    const Lanes3 a = corner2(first[0], second[0]);
    const Lanes3 u = sub2(corner2(first[1], second[1]), a);
    const Lanes3 v = sub2(corner2(first[2], second[2]), a);
    const Lanes3 w = sub2(corner2(first[3], second[3]), a);
    const Lanes3 vw = cross2(v, w), wu = cross2(w, u), uv = cross2(u, v);
    const __m128d det = dot2(u, vw);
    const __m128d area2 = _mm_add_pd(_mm_add_pd(_mm_add_pd(len2(uv), len2(wu)), len2(vw)),
                                     len2(cross2(sub2(v, u), sub2(w, u))));
    const __m128d uu = dot2(u, u), vv = dot2(v, v), ww = dot2(w, w);
    const auto mix = [&](__m128d p, __m128d q, __m128d r) {
        return _mm_add_pd(_mm_add_pd(_mm_mul_pd(uu, p), _mm_mul_pd(vv, q)), _mm_mul_pd(ww, r));
    };
    const Lanes3 n = {mix(vw.x, wu.x, uv.x), mix(vw.y, wu.y, uv.y), mix(vw.z, wu.z, uv.z)};
    const __m128d denominator = _mm_mul_pd(area2, len2(n));
    const __m128d q = _mm_div_pd(_mm_mul_pd(_mm_mul_pd(_mm_set1_pd(6), det), det), denominator);
    double lanes[2], denominators[2];
    _mm_storeu_pd(lanes, q);
    _mm_storeu_pd(denominators, denominator);
    const double* const* corners[2] = {first, second};
    for (int k = 0; k < 2; ++k) {
        const double d = denominators[k];
        if (!(d >= 1e-280 && d <= 1e280)) {  // the scalar path scales the edges
            const double* const* c = corners[k];
            out[k] = radius_ratio(c[0], c[1], c[2], c[3]);
        } else {
            out[k] = std::isfinite(lanes[k]) ? std::clamp(lanes[k], 0.0, 1.0) : 0;
        }
    }
#else
    out[0] = radius_ratio(first[0], first[1], first[2], first[3]);
    out[1] = radius_ratio(second[0], second[1], second[2], second[3]);
#endif
}

void radius_ratios(const mesh::TetMesh& m, const mesh::TetId* tets, std::size_t count, double* out) {
    each_radius_ratio(
        count, [&](std::size_t k, const double* c[4]) { corner_points(m, tets[k], c); },
        [&](double q) {
            *out++ = q;
            return true;
        });
}

double oriented_radius_ratio(const double* a, const double* b, const double* c, const double* d) {
    if (geom::orient3d(a, b, c, d) <= 0) return -std::numeric_limits<double>::infinity();
    return radius_ratio(a, b, c, d);
}

namespace {

// The dihedral angle at each edge of kTetEdges as a pair (sine, cosine),
// both times one positive factor, from the unit edges at a (unit_edges):
// the angle is atan2(sine, cosine).
void dihedral_pairs(const V& u, const V& v, const V& w, std::array<double, 6>& sine,
                    std::array<double, 6>& cosine) {
    const V p[4] = {V{0, 0, 0}, u, v, w};
#if defined(__SSE2__)
    // Two edges at a time (Lanes3), each lane bit for bit the loop below.
    for (std::size_t i = 0; i < 6; i += 2) {
        const auto& e = kTetEdges[i];
        const auto& f = kTetEdges[i + 1];
        const auto at = [&](int k) {
            return corner2(p[e[static_cast<std::size_t>(k)]].data(), p[f[static_cast<std::size_t>(k)]].data());
        };
        const Lanes3 corner = at(0);
        const Lanes3 axis = sub2(at(1), corner);
        const Lanes3 n1 = cross2(axis, sub2(at(2), corner)), n2 = cross2(axis, sub2(at(3), corner));
        _mm_storeu_pd(&sine[i], len2(cross2(n1, n2)));
        _mm_storeu_pd(&cosine[i], dot2(n1, n2));
    }
#else
    for (std::size_t i = 0; i < 6; ++i) {
        const auto& e = kTetEdges[i];
        const auto at = [&](int k) { return p[e[static_cast<std::size_t>(k)]]; };
        const V axis = sub(at(1), at(0));
        const V n1 = cross(axis, sub(at(2), at(0))), n2 = cross(axis, sub(at(3), at(0)));
        sine[i] = len(cross(n1, n2));
        cosine[i] = dot(n1, n2);
    }
#endif
}

// Angle i of the pairs is below angle j: both in [0, 180] deg, so the sine
// of their difference, s_i c_j - c_i s_j, is negative; where it is 0 the
// directions are parallel (equal angles, or 0 against 180 deg, told apart
// by the cosine). A vanishing pair, (0, 0), is atan2's 0 deg; it comes only
// with four coplanar corners, whose other angles are 0 or 180, and against
// those the cosine tells it right.
bool angle_below(const std::array<double, 6>& sine, const std::array<double, 6>& cosine, std::size_t i,
                 std::size_t j) {
    const double difference = sine[i] * cosine[j] - cosine[i] * sine[j];
    return difference != 0 ? difference < 0 : cosine[i] > cosine[j];
}

// The smallest of the six angles (angle_below).
std::size_t smallest_angle(const std::array<double, 6>& sine, const std::array<double, 6>& cosine) {
    std::size_t smallest = 0;
    for (std::size_t i = 1; i < 6; ++i)
        if (angle_below(sine, cosine, i, smallest)) smallest = i;
    return smallest;
}

double degrees_of(const std::array<double, 6>& sine, const std::array<double, 6>& cosine, std::size_t i) {
    return std::atan2(sine[i], cosine[i]) * (180 / kPi);
}

// dihedral_pairs of abcd from its unit edges; false when it has no extent
// in double (unit_edges).
bool dihedral_pairs(const double* a, const double* b, const double* c, const double* d, std::array<double, 6>& sine,
                    std::array<double, 6>& cosine) {
    V u, v, w;
    if (!unit_edges(a, b, c, d, u, v, w)) return false;
    dihedral_pairs(u, v, w, sine, cosine);
    return true;
}

}  // namespace

bool dihedral_angles(const double* a, const double* b, const double* c, const double* d,
                     std::array<double, 6>& deg) {
    std::array<double, 6> sine, cosine;
    if (!dihedral_pairs(a, b, c, d, sine, cosine)) {
        deg.fill(0);
        return false;
    }
    for (std::size_t i = 0; i < 6; ++i) deg[i] = degrees_of(sine, cosine, i);
    return true;
}

// The smallest and largest of the six angles are picked by signs
// (angle_below), and only they take an arctangent: two instead of six
// (the six were most of the cost of smoothing for the angle, and of
// Table II after cbr_mesh_refine). Two angles equal within rounding might
// be told apart differently than by their arctangents, by an ulp; on
// 60,000 test shapes the values are those of dihedral_angles, bit for bit
// (test_refine).
void dihedral_range(const double* a, const double* b, const double* c, const double* d, double& min_deg,
                    double& max_deg) {
    std::array<double, 6> sine, cosine;
    if (!dihedral_pairs(a, b, c, d, sine, cosine)) {
        min_deg = max_deg = 0;
        return;
    }
    std::size_t largest = 0;
    for (std::size_t i = 1; i < 6; ++i)
        if (angle_below(sine, cosine, largest, i)) largest = i;
    min_deg = degrees_of(sine, cosine, smallest_angle(sine, cosine));
    max_deg = degrees_of(sine, cosine, largest);
}

// dihedral_range's minimum alone: one arctangent.
double min_dihedral(const double* a, const double* b, const double* c, const double* d) {
    std::array<double, 6> sine, cosine;
    if (!dihedral_pairs(a, b, c, d, sine, cosine)) return 0;
    return degrees_of(sine, cosine, smallest_angle(sine, cosine));
}

double oriented_min_dihedral(const double* a, const double* b, const double* c, const double* d) {
    if (geom::orient3d(a, b, c, d) <= 0) return -std::numeric_limits<double>::infinity();
    return min_dihedral(a, b, c, d);
}

double radius_ratio_bound_for_dihedral(double degrees) { return 6 * std::sin(degrees * (kPi / 360)); }

bool has_dihedral_below(const mesh::TetMesh& m, mesh::TetId t, double degrees, double q_bound) {
    if (radius_ratio(m, t) >= q_bound) return false;
    const mesh::VertexId* v = m.vertices(t);
    return min_dihedral(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])) < degrees;
}

// 3 r / R = 3 (A / s) / (xyz / 4A) = 24 A^2 / (perimeter xyz), x, y, z the
// edge lengths, A^2 = |(b - a) x (c - a)|^2 / 4; with the perimeter taken
// as twice the longest edge L (at most 1.5 times too small, and exact in
// the limit on needles and flat caps, the faces for which the bound is
// small): 3 |n|^2 / (L xyz), one square root. Squares are divided by L^2
// so that nothing overflows. 1.5 (no information) when the triangle has
// no extent in double.
double radius_ratio_bound_for_face(const double* a, const double* b, const double* c) {
    const V u = sub(b, a), w = sub(c, a);
    const double x2 = dot(u, u), y2 = dot(sub(w, u), sub(w, u)), z2 = dot(w, w);
    const double longest2 = std::max({x2, y2, z2});
    if (!(longest2 > 0) || !std::isfinite(longest2)) return 1.5;
    const V n = cross(mul(u, 1 / longest2), w);  // |n| / L^2
    const double product = (x2 / longest2) * (y2 / longest2) * (z2 / longest2);  // (xyz / L^3)^2
    if (!(product > 0)) return 1.5;
    return std::min(1.5, 3 * dot(n, n) / std::sqrt(product));
}

bool circumcentre(const double* a, const double* b, const double* c, const double* d, Point& centre) {
    const V u = sub(b, a), v = sub(c, a), w = sub(d, a);
    const V vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
    const double det = dot(u, vw);
    if (det == 0 || !std::isfinite(det)) return false;
    const double uu = dot(u, u), vv = dot(v, v), ww = dot(w, w);
    const double s = 1 / (2 * det);
    for (int k = 0; k < 3; ++k) centre[k] = a[k] + (uu * vw[k] + vv * wu[k] + ww * uv[k]) * s;
    return std::isfinite(centre[0]) && std::isfinite(centre[1]) && std::isfinite(centre[2]);
}

bool triangle_circumsphere(const double* a, const double* b, const double* c, Point& centre, double& radius2) {
    const V u = sub(b, a), v = sub(c, a);
    const V n = cross(u, v);
    const double nn = dot(n, n);
    if (!(nn > 0)) return false;
    // centre - a = (|u|^2 (v x n) + |v|^2 (n x u)) / (2 |n|^2)
    const V t1 = mul(cross(v, n), dot(u, u)), t2 = mul(cross(n, u), dot(v, v));
    const V r = {(t1[0] + t2[0]) / (2 * nn), (t1[1] + t2[1]) / (2 * nn), (t1[2] + t2[2]) / (2 * nn)};
    for (int k = 0; k < 3; ++k) centre[k] = a[k] + r[k];
    radius2 = dot(r, r);
    return std::isfinite(radius2);
}

double radius_edge_ratio(const double* a, const double* b, const double* c, const double* d) {
    Point cc;
    if (!circumcentre(a, b, c, d, cc)) return std::numeric_limits<double>::infinity();
    const double r2 = squared_distance(cc.data(), a);
    const double shortest = std::min({squared_distance(a, b), squared_distance(a, c), squared_distance(a, d),
                                      squared_distance(b, c), squared_distance(b, d), squared_distance(c, d)});
    if (!(shortest > 0)) return std::numeric_limits<double>::infinity();
    return std::sqrt(r2 / shortest);
}

void add_apexes(const double* a, const double* b, const double* d, const double* heights, std::size_t count,
                std::vector<Point>& out) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) return;
    const double edge =
        (std::sqrt(squared_distance(a, b)) + std::sqrt(squared_distance(b, d)) + std::sqrt(squared_distance(a, d))) / 3;
    for (std::size_t h = 0; h < count; ++h) {
        Point p;
        for (int i = 0; i < 3; ++i) p[i] = (a[i] + b[i] + d[i]) / 3 + heights[h] * edge * n[i] / len;
        out.push_back(p);
    }
}

}  // namespace cbr::refine

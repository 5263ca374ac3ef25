// Exact stages of the predicates and the symbolic perturbation (the
// floating-point filters are inline in predicates.hpp).
//
// Why the supported range makes everything exact. A coordinate of
// magnitude in [1e-40, 1e+40] (or 0) is an integer multiple of 2^-185
// (1e-40 > 2^-133, whose binade has ulp 2^-185) and smaller than 2^133.
// Every value computed below, in the filters as in the exact stages, is a
// polynomial of degree <= 5 with small integer coefficients in the
// coordinates, or a rounding of one; rounding a multiple of 2^-g (g <= 1074)
// gives a multiple of 2^-g. So every non-zero intermediate is a multiple of
// 2^-925 > 2^-1022: never subnormal, hence no underflow, and the error terms
// of two_sum / two_product (themselves multiples of that grid) are exact.
// At the other end every intermediate is below the sum of the absolute
// values of the monomials, < 2^680 for the degree-5 insphere determinant on
// raw coordinates (and smaller elsewhere): no overflow, and the Dekker split
// (which needs |x| < 2^996) is valid.
//
// Exact stages first try coordinate differences: when every difference is
// a double (two_diff has no error; the usual case for nearby points, by
// Sterbenz's lemma, and for grids), the determinant is evaluated on them as
// short expansions. Otherwise the general "raw" form, expanded on the raw
// coordinates, is used; it is always exact but longer (up to 5760
// components for insphere: about 170 KB of stack in that rare path).
#include "geom/predicates.hpp"

#include <cmath>

#include "geom/expansion.hpp"
#include "geom/plane_side.hpp"

namespace cbr::geom {
namespace {

using xp::Expansion;
using xp::minor2;

// Four points with one coordinate equal lie in a plane parallel to the
// axes: a column of b-a, c-a, d-a is exactly zero, and so is the
// determinant, whatever the other coordinates.
bool on_one_axis_plane(const double* a, const double* b, const double* c, const double* d) {
    for (int k = 0; k < 3; ++k)
        if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k]) return true;
    return false;
}

// Projection of 3D points onto a coordinate plane: drop coordinate `drop`
// and keep the two others in cyclic order, so that the 2D orientation of
// projected points equals component `drop` of the 3D cross product.
struct Projection {
    int i;
    int j;
    explicit Projection(int drop) : i((drop + 1) % 3), j((drop + 2) % 3) {}
};

// out = p - o, coordinate by coordinate; false when a difference is not
// exactly representable.
bool exact_differences(const double* p, const double* o, double* out) {
    bool exact = true;
    for (int k = 0; k < 3; ++k) {
        double err;
        xp::two_diff(p[k], o[k], out[k], err);
        exact = exact && err == 0.0;
    }
    return exact;
}

// Exact p_x * p_x * x + p_y * p_y * x + p_z * p_z * x = |p|^2 x.
// Compressed: the lifted terms are summed next. (Callers also compress x
// when it comes from a long formula: the products then work on a few
// components instead of the worst-case count.)
template <int N>
Expansion<12 * N> lifted(const double* p, const Expansion<N>& x) {
    Expansion<12 * N> r = (p[0] * (p[0] * x) + p[1] * (p[1] * x)) + p[2] * (p[2] * x);
    xp::compress(r);
    return r;
}

// det[p; q; r] = pz m(q,r) - qz m(p,r) + rz m(p,q) from the xy minors.
Expansion<24> det3_from_minors(double pz, double qz, double rz, const Expansion<4>& m_qr,
                               const Expansion<4>& m_pr, const Expansion<4>& m_pq) {
    return (pz * m_qr - qz * m_pr) + rz * m_pq;
}

// xy minor m(p, q) = px qy - qx py.
Expansion<4> xy_minor(const double* p, const double* q) {
    return minor2(p[0], q[1], q[0], p[1]);
}

// ---- determinants whose every step is exact in doubles --------------------
// Coordinates with few significant bits (CAD grids, upsampled flat faces)
// make every product and sum of a small determinant exact: its rounded value
// is then the determinant, and the expansions are not needed. Each step is
// checked by its error term (an explicit fma or two_sum); a product near the
// underflow range is not trusted (its error could round to 0).

template <bool kFma>
[[gnu::always_inline]] inline bool exact_product(double a, double b, double& p) {
    double err;
    if constexpr (kFma) {
        p = a * b;
        err = __builtin_fma(a, b, -p);
    } else {
        xp::two_product(a, b, p, err);
    }
    return err == 0.0 && (p == 0.0 || std::fabs(p) > 0x1p-900);
}

[[gnu::always_inline]] inline bool exact_sum(double a, double b, double& s) {
    double err;
    xp::two_sum(a, b, s, err);
    return err == 0.0;
}

// m(p, q) = px qy - qx py, when exact.
template <bool kFma>
[[gnu::always_inline]] inline bool exact_xy_minor(const double* p, const double* q, double& m) {
    double l, r;
    return exact_product<kFma>(p[0], q[1], l) && exact_product<kFma>(q[0], p[1], r) && exact_sum(l, -r, m);
}

// det3_from_minors in doubles, when every step is exact.
template <bool kFma>
[[gnu::always_inline]] inline bool det3_steps(const double* u, const double* v, const double* w, double& det) {
    double m_vw, m_uw, m_uv, a, b, c, ab;
    return exact_xy_minor<kFma>(v, w, m_vw) && exact_xy_minor<kFma>(u, w, m_uw) &&
           exact_xy_minor<kFma>(u, v, m_uv) && exact_product<kFma>(u[2], m_vw, a) &&
           exact_product<kFma>(v[2], m_uw, b) && exact_product<kFma>(w[2], m_uv, c) && exact_sum(a, -b, ab) &&
           exact_sum(ab, c, det);
}

// The normal (b - a) x (c - a) of a plane from u = b - a, v = c - a, and
// the dot product of x - a with it, in doubles when every step is exact
// (PlaneSide's exact stage on CAD coordinates).
template <bool kFma>
[[gnu::always_inline]] inline bool normal_steps(const double* u, const double* v, double* n) {
    double l, r;
    return exact_product<kFma>(u[1], v[2], l) && exact_product<kFma>(v[1], u[2], r) && exact_sum(l, -r, n[0]) &&
           exact_product<kFma>(u[2], v[0], l) && exact_product<kFma>(v[2], u[0], r) && exact_sum(l, -r, n[1]) &&
           exact_product<kFma>(u[0], v[1], l) && exact_product<kFma>(v[0], u[1], r) && exact_sum(l, -r, n[2]);
}

template <bool kFma>
[[gnu::always_inline]] inline bool dot_steps(const double* w, const double* n, double& dot) {
    double a, b, c, ab;
    return exact_product<kFma>(w[0], n[0], a) && exact_product<kFma>(w[1], n[1], b) &&
           exact_product<kFma>(w[2], n[2], c) && exact_sum(a, b, ab) && exact_sum(ab, c, dot);
}

// A portable x86-64 build may not assume a fused multiply-add, but most
// processors have one: the fma steps are compiled for it apart, and taken
// when the processor says so (fma_available).
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__)) && !defined(FP_FAST_FMA)
#define CBR_FMA_AT_RUN_TIME 1
[[gnu::target("fma")]] bool det3_steps_fma(const double* u, const double* v, const double* w, double& det) {
    return det3_steps<true>(u, v, w, det);
}
[[gnu::target("fma")]] bool normal_steps_fma(const double* u, const double* v, double* n) {
    return normal_steps<true>(u, v, n);
}
[[gnu::target("fma")]] bool dot_steps_fma(const double* w, const double* n, double& dot) {
    return dot_steps<true>(w, n, dot);
}
#endif

// Raw 2D orientation det[1, p; 1, q; 1, r] = m(q,r) - m(p,r) + m(p,q).
Expansion<12> orient2d_from_minors(const Expansion<4>& m_qr, const Expansion<4>& m_pr,
                                   const Expansion<4>& m_pq) {
    return (m_qr - m_pr) + m_pq;
}

// ---- orient2d on projected points (incircle_coplanar_sos, collinear) ----

// Filter for det[b-a, c-a] in 2D. n = k = 4 (2 differences, product,
// subtraction / sum): C >= 4u + 36u^2 (see predicates.hpp).
constexpr double kOrient2dErrorFactor = (4.0 + 64.0 * detail::kUnitRoundoff) *
                                        detail::kUnitRoundoff;

int orient2d_exact(const double* a, const double* b, const double* c) {
    double u0, u1, v0, v1, e0, e1, e2, e3;
    xp::two_diff(b[0], a[0], u0, e0);
    xp::two_diff(b[1], a[1], u1, e1);
    xp::two_diff(c[0], a[0], v0, e2);
    xp::two_diff(c[1], a[1], v1, e3);
    if (e0 == 0.0 && e1 == 0.0 && e2 == 0.0 && e3 == 0.0) {
        return minor2(u0, v1, v0, u1).sign();
    }
    return orient2d_from_minors(xy_minor(b, c), xy_minor(a, c), xy_minor(a, b)).sign();
}

// Sign of det[b-a, c-a] for 2D points.
int orient2d(const double* a, const double* b, const double* c) {
    const double ux = b[0] - a[0], uy = b[1] - a[1];
    const double vx = c[0] - a[0], vy = c[1] - a[1];
    const double p1 = ux * vy, p2 = vx * uy;
    const double det = p1 - p2;
    const double bound = kOrient2dErrorFactor * (std::fabs(p1) + std::fabs(p2));
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return orient2d_exact(a, b, c);
}

// orient2d of the projections of three 3D points.
int orient2d_projected(const double* a, const double* b, const double* c, Projection pr) {
    const double a2[2] = {a[pr.i], a[pr.j]};
    const double b2[2] = {b[pr.i], b[pr.j]};
    const double c2[2] = {c[pr.i], c[pr.j]};
    return orient2d(a2, b2, c2);
}

// ---- orient3d -------------------------------------------------------------

Expansion<96> orient3d_raw_expansion(const double* a, const double* b, const double* c,
                                     const double* d) {
    // det[1, p] over rows a, b, c, d, expanded along z:
    //   -az O2(bcd) + bz O2(acd) - cz O2(abd) + dz O2(abc).
    const Expansion<4> m_ab = xy_minor(a, b), m_ac = xy_minor(a, c), m_ad = xy_minor(a, d);
    const Expansion<4> m_bc = xy_minor(b, c), m_bd = xy_minor(b, d), m_cd = xy_minor(c, d);
    const auto o_bcd = orient2d_from_minors(m_cd, m_bd, m_bc);
    const auto o_acd = orient2d_from_minors(m_cd, m_ad, m_ac);
    const auto o_abd = orient2d_from_minors(m_bd, m_ad, m_ab);
    const auto o_abc = orient2d_from_minors(m_bc, m_ac, m_ab);
    return (b[2] * o_acd - a[2] * o_bcd) + (d[2] * o_abc - c[2] * o_abd);
}

// ---- insphere -------------------------------------------------------------

// -det[p', |p'|^2] over rows a', b', c', d' (p' = p - e, exact doubles):
//   l_a T(bcd) - l_b T(acd) + l_c T(abd) - l_d T(abc), as in the filter.
int insphere_from_differences(const double* a, const double* b, const double* c,
                              const double* d) {
    const Expansion<4> m_ab = xy_minor(a, b), m_ac = xy_minor(a, c), m_ad = xy_minor(a, d);
    const Expansion<4> m_bc = xy_minor(b, c), m_bd = xy_minor(b, d), m_cd = xy_minor(c, d);
    auto t_abc = det3_from_minors(a[2], b[2], c[2], m_bc, m_ac, m_ab);
    auto t_abd = det3_from_minors(a[2], b[2], d[2], m_bd, m_ad, m_ab);
    auto t_acd = det3_from_minors(a[2], c[2], d[2], m_cd, m_ad, m_ac);
    auto t_bcd = det3_from_minors(b[2], c[2], d[2], m_cd, m_bd, m_bc);
    xp::compress(t_abc);
    xp::compress(t_abd);
    xp::compress(t_acd);
    xp::compress(t_bcd);
    const auto value = (lifted(a, t_bcd) - lifted(b, t_acd)) + (lifted(c, t_abd) - lifted(d, t_abc));
    return value.sign();
}

// The raw orientation O3 = det[1, p] of the four points other than `skip`
// among five, in their order.
struct RawMinors5 {
    Expansion<4> m[5][5];  // m[i][j] = xy minor of points i < j

    explicit RawMinors5(const double* const* p) {
        for (int i = 0; i < 5; ++i) {
            for (int j = i + 1; j < 5; ++j) m[i][j] = xy_minor(p[i], p[j]);
        }
    }

    Expansion<12> o2(int i, int j, int k) const {  // i < j < k
        return orient2d_from_minors(m[j][k], m[i][k], m[i][j]);
    }

    Expansion<96> orient3d_without(const double* const* p, int skip) const {
        int r[4];
        for (int i = 0, n = 0; i < 5; ++i) {
            if (i != skip) r[n++] = i;
        }
        Expansion<96> o3 =
            (p[r[1]][2] * o2(r[0], r[2], r[3]) - p[r[0]][2] * o2(r[1], r[2], r[3])) +
            (p[r[3]][2] * o2(r[0], r[1], r[2]) - p[r[2]][2] * o2(r[0], r[1], r[3]));
        xp::compress(o3);
        return o3;
    }
};

// Term i of -det[1, p, |p|^2] expanded along the lift column:
// (-1)^(i+1) |p_i|^2 O3(the others).
[[gnu::noinline]] Expansion<1152> raw_lifted_term(const double* const* p,
                                                  const RawMinors5& minors, int i) {
    const Expansion<96> o3 = minors.orient3d_without(p, i);
    return i % 2 == 0 ? lifted(p[i], -o3) : lifted(p[i], o3);
}

[[gnu::noinline]] Expansion<2304> raw_pair_sum(const double* const* p, const RawMinors5& minors,
                                               int i, int j) {
    return raw_lifted_term(p, minors, i) + raw_lifted_term(p, minors, j);
}

// ---- symbolic perturbation -------------------------------------------------

// Sorts the indices of n points by increasing lexicographic order; false
// when two points coincide.
template <int N>
bool lexicographic_order(const double* const* p, int* order) {
    for (int i = 0; i < N; ++i) order[i] = i;
    for (int i = 1; i < N; ++i) {  // insertion sort, N <= 5
        for (int k = i; k > 0; --k) {
            const int cmp = lexicographic_compare(p[order[k - 1]], p[order[k]]);
            if (cmp == 0) return false;
            if (cmp < 0) break;
            const int t = order[k - 1];
            order[k - 1] = order[k];
            order[k] = t;
        }
    }
    return true;
}

// The perturbed determinant -det[1, p, |p|^2 + eps^k(p)] is
// D0 - sum_i eps^k(i) C_i, C_i = (-1)^(i+5) O3(others) (rows 1-based), so the
// term of point i (0-based) has the sign of (-1)^(i+1) orient3d(others).
// The lexicographically smallest point has k = 1, the dominant term.
int insphere_perturbed(const double* const* p, PredicateCounters* counters) {
    int order[5];
    if (!lexicographic_order<5>(p, order)) return 0;  // two equal rows: identically 0
    if (counters) ++counters->insphere_perturbed;
    for (int n = 0; n < 5; ++n) {
        const int i = order[n];
        const double* q[4];
        for (int k = 0, m = 0; k < 5; ++k) {
            if (k != i) q[m++] = p[k];
        }
        const int s = orient3d(q[0], q[1], q[2], q[3], counters);
        if (s != 0) return i % 2 == 0 ? -s : s;
    }
    return 0;  // all five points coplanar
}

// ---- incircle_coplanar_sos ----------------------------------------------

// With u = b-a, v = c-a, w = p-a and the projection (i, j): the lifted 2D
// determinant M = det[u_i u_j |u|^2; v_i v_j |v|^2; w_i w_j |w|^2] with 3D
// squared norms. Since w = alpha u + beta v (coplanarity), subtracting
// alpha row1 + beta row2 from row3 gives M = kappa * det[u_i u_j; v_i v_j],
// kappa = |w|^2 - alpha |u|^2 - beta |v|^2, the same kappa for every
// projection; and insphere_sos(a, b, c, q, p) unperturbed is
// -kappa * orient3d(a, b, c, q) (same row operation in 4D).
//
// Filter: n = k = 12 (4 differences, lift: product and 2 additions, minor:
// product and subtraction, product, 2 additions): C >= 12u + 300u^2.
constexpr double kLiftedIncircleErrorFactor = (12.0 + 512.0 * detail::kUnitRoundoff) *
                                              detail::kUnitRoundoff;

int lifted_incircle_filter(const double* a, const double* b, const double* c, const double* p,
                           Projection pr) {
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = p[k] - a[k];
    }
    const double lu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    const double lv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    const double lw = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    const double vw1 = v[pr.i] * w[pr.j], vw2 = w[pr.i] * v[pr.j];
    const double uw1 = u[pr.i] * w[pr.j], uw2 = w[pr.i] * u[pr.j];
    const double uv1 = u[pr.i] * v[pr.j], uv2 = v[pr.i] * u[pr.j];
    const double det = lu * (vw1 - vw2) - lv * (uw1 - uw2) + lw * (uv1 - uv2);
    const double permanent = lu * (std::fabs(vw1) + std::fabs(vw2)) +
                             lv * (std::fabs(uw1) + std::fabs(uw2)) +
                             lw * (std::fabs(uv1) + std::fabs(uv2));
    const double bound = kLiftedIncircleErrorFactor * permanent;
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return 0;
}

// Exact sign of M. On raw coordinates M equals (given coplanarity)
// R = det[1, p_i, p_j, |p|^2] over rows a, b, c, p: subtracting row a and
// column operations give M + 2 a_k det[u; v; w] (k the dropped axis), and
// det[u; v; w] = orient3d(a, b, c, p) = 0.
int lifted_incircle_exact(const double* a, const double* b, const double* c, const double* p,
                          Projection pr) {
    double u[3], v[3], w[3];
    const bool exact = exact_differences(b, a, u) & exact_differences(c, a, v) &
                       exact_differences(p, a, w);
    auto minor = [pr](const double* x, const double* y) {
        return minor2(x[pr.i], y[pr.j], y[pr.i], x[pr.j]);
    };
    if (exact) {
        return ((lifted(u, minor(v, w)) - lifted(v, minor(u, w))) + lifted(w, minor(u, v))).sign();
    }
    const Expansion<4> m_ab = minor(a, b), m_ac = minor(a, c), m_ap = minor(a, p);
    const Expansion<4> m_bc = minor(b, c), m_bp = minor(b, p), m_cp = minor(c, p);
    // R = -|a|^2 O2(bcp) + |b|^2 O2(acp) - |c|^2 O2(abp) + |p|^2 O2(abc).
    using xp::compressed;
    const auto r = (lifted(b, compressed(orient2d_from_minors(m_cp, m_ap, m_ac))) -
                    lifted(a, compressed(orient2d_from_minors(m_cp, m_bp, m_bc)))) +
                   (lifted(p, compressed(orient2d_from_minors(m_bc, m_ac, m_ab))) -
                    lifted(c, compressed(orient2d_from_minors(m_bp, m_ap, m_ab))));
    return r.sign();
}

// A projection in which abc does not degenerate, and the sign s of the
// projected orient2d(a, b, c); s = 0 when a, b, c are collinear. Tries the
// axis of the largest approximate normal component first.
int plane_projection(const double* a, const double* b, const double* c, int& drop) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {std::fabs(u[1] * v[2] - u[2] * v[1]),
                         std::fabs(u[2] * v[0] - u[0] * v[2]),
                         std::fabs(u[0] * v[1] - u[1] * v[0])};
    const int best = n[0] >= n[1] ? (n[0] >= n[2] ? 0 : 2) : (n[1] >= n[2] ? 1 : 2);
    for (int t = 0; t < 3; ++t) {
        drop = (best + t) % 3;
        const int s = orient2d_projected(a, b, c, Projection(drop));
        if (s != 0) return s;
    }
    return 0;
}

// The perturbation terms of insphere_sos(a, b, c, q, p) for q above the
// plane: for x in {a, b, c} the cofactor is an orient3d(., ., ., q) whose
// sign is s * (projected orient2d of the triangle with x replaced by p):
// a -> (p, b, c), b -> (a, p, c), c -> (a, b, p); q's own cofactor is
// orient3d(a, b, c, p) = 0; p's term is -orient3d(a, b, c, q) < 0.
int incircle_perturbed(const double* const* pts, int s, Projection pr) {
    int order[4];
    if (!lexicographic_order<4>(pts, order)) return 0;  // p coincides with a, b or c
    const double* a = pts[0];
    const double* b = pts[1];
    const double* c = pts[2];
    const double* p = pts[3];
    for (int n = 0; n < 4; ++n) {
        int t = 0;
        switch (order[n]) {
            case 0: t = orient2d_projected(p, b, c, pr); break;
            case 1: t = orient2d_projected(a, p, c, pr); break;
            case 2: t = orient2d_projected(a, b, p, pr); break;
            default: return -1;
        }
        if (t != 0) return s * t;
    }
    return -1;  // not reached: p's term is last at the latest
}

}  // namespace

// ---- public and detail entry points -------------------------------------

namespace detail {

bool fma_available() {
#if defined(CBR_FMA_AT_RUN_TIME)
    static const bool available = __builtin_cpu_supports("fma");
    return available;
#elif defined(FP_FAST_FMA)
    return true;
#else
    return false;
#endif
}

bool det3_in_doubles(const double* u, const double* v, const double* w, double& det, bool fma) {
#if defined(CBR_FMA_AT_RUN_TIME)
    if (fma) return det3_steps_fma(u, v, w, det);
#elif defined(FP_FAST_FMA)
    if (fma) return det3_steps<true>(u, v, w, det);
#else
    (void)fma;
#endif
    return det3_steps<false>(u, v, w, det);
}

bool normal_in_doubles(const double* u, const double* v, double* n, bool fma) {
#if defined(CBR_FMA_AT_RUN_TIME)
    if (fma) return normal_steps_fma(u, v, n);
#elif defined(FP_FAST_FMA)
    if (fma) return normal_steps<true>(u, v, n);
#else
    (void)fma;
#endif
    return normal_steps<false>(u, v, n);
}

bool dot_in_doubles(const double* w, const double* n, double& dot, bool fma) {
#if defined(CBR_FMA_AT_RUN_TIME)
    if (fma) return dot_steps_fma(w, n, dot);
#elif defined(FP_FAST_FMA)
    if (fma) return dot_steps<true>(w, n, dot);
#else
    (void)fma;
#endif
    return dot_steps<false>(w, n, dot);
}

int orient3d_exact_raw(const double* a, const double* b, const double* c, const double* d) {
    return orient3d_raw_expansion(a, b, c, d).sign();
}

int orient3d_exact(const double* a, const double* b, const double* c, const double* d,
                   PredicateCounters* counters) {
    if (counters) ++counters->orient3d_exact;
    // Two equal points make two rows of the determinant equal, four points
    // on one axis-parallel plane a zero column: exactly 0, without the
    // expansions. The filter cannot decide such degenerate cases, and
    // callers meet them all the time (a segment tested against the faces
    // around its own endpoint; ring triangulations on the flat faces of
    // CAD parts: 15% of the feeder body's recovery was spent there).
    if (same_point(a, b) || same_point(a, c) || same_point(a, d) || same_point(b, c) || same_point(b, d) ||
        same_point(c, d) || on_one_axis_plane(a, b, c, d))
        return 0;
    double u[3], v[3], w[3];
    if (exact_differences(b, a, u) & exact_differences(c, a, v) & exact_differences(d, a, w)) {
        double det;
        if (det3_in_doubles(u, v, w, det, fma_available())) return (det > 0) - (det < 0);
        const Expansion<4> m_uv = xy_minor(u, v), m_uw = xy_minor(u, w), m_vw = xy_minor(v, w);
        return det3_from_minors(u[2], v[2], w[2], m_vw, m_uw, m_uv).sign();
    }
    return orient3d_exact_raw(a, b, c, d);
}

// -det[1, p, |p|^2] over rows a, b, c, d, e on raw coordinates.
[[gnu::noinline]] int insphere_exact_raw(const double* a, const double* b, const double* c,
                                         const double* d, const double* e) {
    const double* p[5] = {a, b, c, d, e};
    const RawMinors5 minors(p);
    const Expansion<2304> t01 = raw_pair_sum(p, minors, 0, 1);
    const Expansion<2304> t23 = raw_pair_sum(p, minors, 2, 3);
    const Expansion<4608> t0123 = t01 + t23;
    return (t0123 + raw_lifted_term(p, minors, 4)).sign();
}

int insphere_exact(const double* a, const double* b, const double* c, const double* d,
                   const double* e, PredicateCounters* counters) {
    if (counters) ++counters->insphere_exact;
    double ae[3], be[3], ce[3], de[3];
    if (exact_differences(a, e, ae) & exact_differences(b, e, be) & exact_differences(c, e, ce) &
        exact_differences(d, e, de)) {
        return insphere_from_differences(ae, be, ce, de);
    }
    return insphere_exact_raw(a, b, c, d, e);
}

int insphere_sos_exact(const double* a, const double* b, const double* c, const double* d,
                       const double* e, PredicateCounters* counters) {
    const int s = insphere_exact(a, b, c, d, e, counters);
    if (s != 0) return s;
    const double* p[5] = {a, b, c, d, e};
    return insphere_perturbed(p, counters);
}

}  // namespace detail

int incircle_coplanar_sos(const double* a, const double* b, const double* c, const double* p,
                          PredicateCounters* counters) {
    int drop = 2;
    const int s = plane_projection(a, b, c, drop);
    if (s == 0) return 0;  // a, b, c collinear: no plane, no positive side
    const Projection pr(drop);
    // Unperturbed: sign(-kappa) = -sign(M) * s (M = kappa * s * |area|).
    int m = lifted_incircle_filter(a, b, c, p, pr);
    if (m == 0) {
        if (counters) ++counters->insphere_exact;
        m = lifted_incircle_exact(a, b, c, p, pr);
    }
    if (m != 0) return -m * s;
    const double* pts[4] = {a, b, c, p};
    const int r = incircle_perturbed(pts, s, pr);
    if (r != 0 && counters) ++counters->insphere_perturbed;
    return r;
}

bool collinear(const double* a, const double* b, const double* c) {
    for (int drop = 0; drop < 3; ++drop) {
        if (orient2d_projected(a, b, c, Projection(drop)) != 0) return false;
    }
    return true;
}

int lexicographic_compare(const double* p, const double* q) {
    for (int k = 0; k < 3; ++k) {
        if (p[k] < q[k]) return -1;
        if (p[k] > q[k]) return 1;
    }
    return 0;
}

// w . (u x v) with u = b - a, v = c - a, w = x - a: det[u; v; w], the
// determinant orient3d_exact expands along z (exact when the differences
// are). First orient3d_exact's shortcuts (x a corner of the face, or on
// one axis-parallel plane with it: exactly 0); then, when the normal and
// the dot product are exact in doubles (CAD coordinates, flat hull faces),
// their rounded value; the expansions only otherwise.
int PlaneSide::exact_sign(const double* x) {
    if (same_point(x, a_) || same_point(x, b_) || same_point(x, c_) || on_one_axis_plane(a_, b_, c_, x)) return 0;
    if (state_ == Normal::kNotYet) {
        double u[3], v[3];
        if (exact_differences(b_, a_, u) & exact_differences(c_, a_, v)) {
            normal_[0] = xp::minor2(u[1], v[2], v[1], u[2]);  // uy vz - vy uz
            normal_[1] = xp::minor2(u[2], v[0], v[2], u[0]);  // uz vx - vz ux
            normal_[2] = xp::minor2(u[0], v[1], v[0], u[1]);  // ux vy - vx uy
            state_ = Normal::kExact;
            normal_in_doubles_ = detail::normal_in_doubles(u, v, normal_doubles_, detail::fma_available());
        } else {
            state_ = Normal::kInexact;
        }
    }
    double w[3];
    if (state_ == Normal::kInexact || !exact_differences(x, a_, w))
        return detail::orient3d_exact(a_, b_, c_, x, nullptr);
    double dot;
    if (normal_in_doubles_ && detail::dot_in_doubles(w, normal_doubles_, dot, detail::fma_available()))
        return (dot > 0) - (dot < 0);
    return ((w[0] * normal_[0] + w[1] * normal_[1]) + w[2] * normal_[2]).sign();
}

}  // namespace cbr::geom

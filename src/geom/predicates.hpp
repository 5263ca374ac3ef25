// Exact geometric predicates: orient3d, insphere, and their symbolically
// perturbed variants. Each returns the exact sign (-1, 0, +1) of a
// polynomial in the input coordinates.
//
// Evaluation order, in each predicate: a floating-point filter (inline,
// here), then exact expansion arithmetic (predicates.cpp) only when the
// filter cannot decide, then — for the *_sos variants — symbolic
// perturbation when the exact value is zero.
//
// Valid input: finite coordinates that are 0 or of magnitude within
// [1e-40, 1e+40] (checked by the C API). In that range no intermediate of
// the filters or of the exact stage overflows or underflows, so every
// answer is exact (the argument is in predicates.cpp).
//
// No global mutable state: the optional counters belong to the caller.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__GNUC__)
#define CBR_GEOM_COLD [[gnu::cold]]
#else
#define CBR_GEOM_COLD
#endif

namespace cbr::geom {

// Coordinates of the supported range (see above).
inline constexpr double kMinMagnitude = 1e-40;
inline constexpr double kMaxMagnitude = 1e+40;

// How often each stage was reached; owned by the caller (one per mesh), so
// threads never share it. Pass nullptr when not counting.
struct PredicateCounters {
    std::uint64_t orient3d_exact = 0;   // filter failed, exact stage ran
    std::uint64_t insphere_exact = 0;   // insphere, insphere_sos, incircle_coplanar_sos
    std::uint64_t insphere_perturbed = 0;  // exact value was 0, SoS decided
};

// The two points have identical coordinates.
inline bool same_point(const double* p, const double* q) { return p[0] == q[0] && p[1] == q[1] && p[2] == q[2]; }

// Sign of det[b-a, c-a, d-a]: +1 when (a, b, c, d) is positively oriented
// (d on the side of plane abc that (b-a) x (c-a) points to), -1 when
// negatively oriented, 0 when the four points are coplanar.
inline int orient3d(const double* a, const double* b, const double* c, const double* d,
                    PredicateCounters* counters = nullptr);

// For a positively oriented tetrahedron (a, b, c, d): +1 when e lies strictly
// inside its circumsphere, -1 strictly outside, 0 on it. For a negatively
// oriented one the sign is reversed (it is the sign of one polynomial:
// minus the 5x5 lifted determinant det[1, p, |p|^2] over rows a, b, c, d, e).
inline int insphere(const double* a, const double* b, const double* c, const double* d,
                    const double* e, PredicateCounters* counters = nullptr);

// insphere with symbolic perturbation (simulation of simplicity): each point
// p is lifted to |p|^2 + eps^k(p) with k(p) = 1 + (lexicographic (x, y, z)
// rank of p among the five points, 0 for the smallest): the
// lexicographically SMALLEST point gets the dominant perturbation. k is a
// function of the coordinates only, so the answer never depends on ids or
// argument order beyond the determinant's sign rule. Never 0 when
// orient3d(a, b, c, d) != 0 and the five points are pairwise distinct
// (0 when two points coincide: the perturbed determinant then has two
// equal rows). Equal to insphere() whenever that is non-zero.
inline int insphere_sos(const double* a, const double* b, const double* c, const double* d,
                        const double* e, PredicateCounters* counters = nullptr);

// For coplanar a, b, c, p with a, b, c not collinear and p distinct from
// them: the conflict test of p against the ghost tetrahedron (a, b, c, oo)
// whose infinite apex lies on the positive side of abc. Defined as
// insphere_sos(a, b, c, q, p) for any q with orient3d(a, b, c, q) > 0 (the
// answer does not depend on q): +1 when p is inside the circumcircle of abc
// (perturbed), -1 outside. Never 0. (Outside the precondition: 0 when a, b,
// c are collinear or p coincides with one of them; meaningless when p is
// not coplanar.)
int incircle_coplanar_sos(const double* a, const double* b, const double* c, const double* p,
                          PredicateCounters* counters = nullptr);

// True when a, b, c lie on one line (exact).
bool collinear(const double* a, const double* b, const double* c);

// Lexicographic (x, y, z) order of two points; the order the perturbation
// uses. -1, 0 (identical coordinates), +1.
int lexicographic_compare(const double* p, const double* q);

// ---------------------------------------------------------------------------
// Implementation: inline filters, out-of-line exact stages.
// ---------------------------------------------------------------------------
namespace detail {

// Exact stages (predicates.cpp); they count themselves in `counters`.
CBR_GEOM_COLD int orient3d_exact(const double* a, const double* b, const double* c,
                                 const double* d, PredicateCounters* counters);
CBR_GEOM_COLD int insphere_exact(const double* a, const double* b, const double* c,
                                 const double* d, const double* e, PredicateCounters* counters);
// Exact stage, then symbolic perturbation when the exact value is 0.
CBR_GEOM_COLD int insphere_sos_exact(const double* a, const double* b, const double* c,
                                     const double* d, const double* e,
                                     PredicateCounters* counters);

// The general exact evaluations on raw coordinates, which the exact stages
// use when a coordinate difference is not representable; exposed so that
// tests can run them on every input.
int orient3d_exact_raw(const double* a, const double* b, const double* c, const double* d);
int insphere_exact_raw(const double* a, const double* b, const double* c, const double* d,
                       const double* e);

// det[u; v; w] computed in doubles, when every product and sum of its
// minor expansion is exact (false otherwise): the exact stage's shortcut
// for coordinates with few significant bits (CAD grids, upsampled flat
// faces). Each product is checked by its error term: with `fma` one fused
// multiply-add (only when fma_available()), else Dekker's split, about ten
// times the instructions; both give the same answer. On the upsampled box,
// whose flat faces send millions of ring triangles here, the fma cut the
// recovery's instructions by 4.6%.
bool det3_in_doubles(const double* u, const double* v, const double* w, double& det, bool fma);
// Whether the processor has a fused multiply-add (asked once).
bool fma_available();
// PlaneSide's exact stage in doubles: the normal (u x v, u = b - a,
// v = c - a) and w . n, each when every product and sum is exact.
bool normal_in_doubles(const double* u, const double* v, double* n, bool fma);
bool dot_in_doubles(const double* w, const double* n, double& dot, bool fma);

// Filter error bounds. u = 2^-53 is the unit roundoff: for every operation
// whose exact result x is non-zero, fl(x) = x (1 + delta), |delta| <= u (no
// underflow or overflow in the supported range, see predicates.cpp).
//
// The filter evaluates det as a fixed expression tree on the rounded
// differences; expanding it, det_computed = sum_j +-m_j prod_{i in path j}
// (1 + delta_i), where m_j are the monomials of the exact determinant in the
// exact differences, and path j has at most n roundings (the differences
// feeding the monomial, and every operation above them). Hence
// |det_computed - det| <= gamma_n sum_j |m_j|, gamma_n = n u / (1 - n u).
// The permanent P = sum_j |m_j| is evaluated with the same tree on absolute
// values; every term is positive, so each rounding there can only shrink it
// by (1 - u), and the computed P_c >= (1 - u)^k sum_j |m_j| where k counts
// the roundings of the permanent's path including the differences. The test
// det_c > fl(C * P_c) is therefore sound when C (1 - u) >= gamma_n (1 - u)^-k
// (the last (1 - u) for rounding C * P_c), i.e. C >= gamma_n (1 - u)^-(k+1)
// = n u + (n^2 + n (k + 1)) u^2 + O(u^3). We take C = (n + c2 u) u with c2
// a power of two well above n^2 + n (k + 1), which also absorbs the O(u^3)
// terms; C is exact in binary64. The same reasoning as Shewchuk's stage-A
// bounds.
inline constexpr double kUnitRoundoff = 0x1p-53;

// orient3d: n = 8 (3 differences, product, minor subtraction, product by
// the third coordinate, 2 additions); k = 8 (3 differences, product, sum,
// product, 2 additions). Need 8u + 136u^2 + O(u^3).
inline constexpr double kOrient3dErrorFactor = (8.0 + 256.0 * kUnitRoundoff) * kUnitRoundoff;

// insphere: n = 16 (5 differences per monomial, lift: product and 2
// additions, minor: product and subtraction, 3x3: product and 2 additions,
// lift times 3x3, 2 final additions); k = 16 likewise. Need 16u + 528u^2.
inline constexpr double kInsphereErrorFactor = (16.0 + 1024.0 * kUnitRoundoff) * kUnitRoundoff;

// The cheaper bound tried first: each of the 72 monomials of the insphere
// determinant (4 lifts of 3 squares, times 4 minors of 6 products of three
// differences) is at most M^5, M the largest absolute difference, so the
// permanent is at most 72 M^5. M computed is at least (1 - u) M (five
// factors), and the 3 products and the scaling round down by at most
// (1 - u) each: C' (1 - u)^9 >= 72 gamma_16 with C' = 72
// kInsphereErrorFactor, as above.
inline constexpr double kInsphereMaxErrorFactor = 72.0 * kInsphereErrorFactor;

// Sign of det[b-a, c-a, d-a] when the floating-point evaluation decides it,
// 0 when it cannot.
inline int orient3d_filter(const double* a, const double* b, const double* c,
                           const double* d) noexcept {
    const double bax = b[0] - a[0], bay = b[1] - a[1], baz = b[2] - a[2];
    const double cax = c[0] - a[0], cay = c[1] - a[1], caz = c[2] - a[2];
    const double dax = d[0] - a[0], day = d[1] - a[1], daz = d[2] - a[2];
    // Expansion along z: baz m(c,d) - caz m(b,d) + daz m(b,c), with the xy
    // minors m(p,q) = px qy - qx py.
    const double cd1 = cax * day, cd2 = dax * cay;
    const double bd1 = bax * day, bd2 = dax * bay;
    const double bc1 = bax * cay, bc2 = cax * bay;
    const double det = baz * (cd1 - cd2) - caz * (bd1 - bd2) + daz * (bc1 - bc2);
    const double permanent = std::fabs(baz) * (std::fabs(cd1) + std::fabs(cd2)) +
                             std::fabs(caz) * (std::fabs(bd1) + std::fabs(bd2)) +
                             std::fabs(daz) * (std::fabs(bc1) + std::fabs(bc2));
    const double bound = kOrient3dErrorFactor * permanent;
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return 0;
}

// insphere sign when the floating-point evaluation decides it, 0 when it
// cannot. With p' = p - e and l_p = |p'|^2, the value is
//   -det[1, p, |p|^2] = l_a T(bcd) - l_b T(acd) + l_c T(abd) - l_d T(abc),
// T(pqr) = det[p'; q'; r'] = pz m(q,r) - qz m(p,r) + rz m(p,q).
inline int insphere_filter(const double* a, const double* b, const double* c, const double* d,
                           const double* e) noexcept {
    const double aex = a[0] - e[0], aey = a[1] - e[1], aez = a[2] - e[2];
    const double bex = b[0] - e[0], bey = b[1] - e[1], bez = b[2] - e[2];
    const double cex = c[0] - e[0], cey = c[1] - e[1], cez = c[2] - e[2];
    const double dex = d[0] - e[0], dey = d[1] - e[1], dez = d[2] - e[2];

    const double ab1 = aex * bey, ab2 = bex * aey;
    const double ac1 = aex * cey, ac2 = cex * aey;
    const double ad1 = aex * dey, ad2 = dex * aey;
    const double bc1 = bex * cey, bc2 = cex * bey;
    const double bd1 = bex * dey, bd2 = dex * bey;
    const double cd1 = cex * dey, cd2 = dex * cey;
    const double ab = ab1 - ab2, ac = ac1 - ac2, ad = ad1 - ad2;
    const double bc = bc1 - bc2, bd = bd1 - bd2, cd = cd1 - cd2;

    const double abc = aez * bc - bez * ac + cez * ab;
    const double abd = aez * bd - bez * ad + dez * ab;
    const double acd = aez * cd - cez * ad + dez * ac;
    const double bcd = bez * cd - cez * bd + dez * bc;

    const double la = aex * aex + aey * aey + aez * aez;
    const double lb = bex * bex + bey * bey + bez * bez;
    const double lc = cex * cex + cey * cey + cez * cez;
    const double ld = dex * dex + dey * dey + dez * dez;

    const double det = (la * bcd - lb * acd) + (lc * abd - ld * abc);

    // Most points are far from the sphere: the bound by the largest
    // difference decides them for about a third of the permanent's
    // operations (on igea's Delaunay insertion, every test).
    const double mx = std::max(std::max(std::fabs(aex), std::fabs(bex)), std::max(std::fabs(cex), std::fabs(dex)));
    const double my = std::max(std::max(std::fabs(aey), std::fabs(bey)), std::max(std::fabs(cey), std::fabs(dey)));
    const double mz = std::max(std::max(std::fabs(aez), std::fabs(bez)), std::max(std::fabs(cez), std::fabs(dez)));
    const double largest = std::max(mx, std::max(my, mz));
    const double square = largest * largest;
    const double quick = kInsphereMaxErrorFactor * (square * square * largest);
    if (det > quick) return 1;
    if (det < -quick) return -1;

    const double pab = std::fabs(ab1) + std::fabs(ab2), pac = std::fabs(ac1) + std::fabs(ac2);
    const double pad = std::fabs(ad1) + std::fabs(ad2), pbc = std::fabs(bc1) + std::fabs(bc2);
    const double pbd = std::fabs(bd1) + std::fabs(bd2), pcd = std::fabs(cd1) + std::fabs(cd2);
    const double az = std::fabs(aez), bz = std::fabs(bez), cz = std::fabs(cez),
                 dz = std::fabs(dez);
    const double pabc = az * pbc + bz * pac + cz * pab;
    const double pabd = az * pbd + bz * pad + dz * pab;
    const double pacd = az * pcd + cz * pad + dz * pac;
    const double pbcd = bz * pcd + cz * pbd + dz * pbc;
    const double permanent = (la * pbcd + lb * pacd) + (lc * pabd + ld * pabc);

    const double bound = kInsphereErrorFactor * permanent;
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return 0;
}

}  // namespace detail

inline int orient3d(const double* a, const double* b, const double* c, const double* d,
                    PredicateCounters* counters) {
    const int s = detail::orient3d_filter(a, b, c, d);
    return s != 0 ? s : detail::orient3d_exact(a, b, c, d, counters);
}

inline int insphere(const double* a, const double* b, const double* c, const double* d,
                    const double* e, PredicateCounters* counters) {
    const int s = detail::insphere_filter(a, b, c, d, e);
    return s != 0 ? s : detail::insphere_exact(a, b, c, d, e, counters);
}

inline int insphere_sos(const double* a, const double* b, const double* c, const double* d,
                        const double* e, PredicateCounters* counters) {
    const int s = detail::insphere_filter(a, b, c, d, e);
    return s != 0 ? s : detail::insphere_sos_exact(a, b, c, d, e, counters);
}

}  // namespace cbr::geom

#undef CBR_GEOM_COLD

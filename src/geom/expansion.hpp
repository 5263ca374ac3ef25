// Exact floating-point expansion arithmetic (the technique of Priest and
// Shewchuk, "Adaptive precision floating-point arithmetic and fast robust
// geometric predicates", 1997), written for libcbr's predicates.
//
// An expansion is a sum of doubles c[0] + c[1] + ... + c[n-1] whose
// components are ordered by increasing magnitude, strongly nonoverlapping
// and non-zero (zero elimination; the value 0 is the one-component {0}).
// Its sign is the sign of its largest component, c[n-1].
//
// Requirements: IEEE binary64, round-to-nearest-even, every operation
// evaluated as written: the project builds with -ffp-contract=off (a
// contracted a*b-c would break two_product) and without -ffast-math.
// Error-free transformations are exact as long as nothing overflows or
// underflows; see predicates.cpp for why the supported input range
// guarantees that.
//
// Storage: Expansion<N> is a fixed-capacity value on the stack; the
// operators compute the capacity of their result at compile time from the
// worst-case length (sum: A+B, scale by a double: 2A), so no buffer can
// overflow and nothing is allocated on the heap.
#pragma once

#include <cfloat>
#include <cmath>

#if defined(__FAST_MATH__)
#error "expansion arithmetic needs IEEE semantics: do not build with -ffast-math"
#endif
#if FLT_EVAL_METHOD != 0
#error "expansion arithmetic needs doubles evaluated in double precision (SSE2, not x87)"
#endif

namespace cbr::geom::xp {

// ---- error-free transformations ------------------------------------------

// s + err == a + b exactly, s = fl(a + b) (Knuth's branch-free two-sum).
inline void two_sum(double a, double b, double& s, double& err) noexcept {
    s = a + b;
    const double b_virtual = s - a;
    const double a_virtual = s - b_virtual;
    err = (a - a_virtual) + (b - b_virtual);
}

// Same, valid only when |a| >= |b| or a == 0 (Dekker's fast two-sum).
inline void fast_two_sum(double a, double b, double& s, double& err) noexcept {
    s = a + b;
    err = b - (s - a);
}

// s + err == a - b exactly (negation is exact).
inline void two_diff(double a, double b, double& s, double& err) noexcept {
    two_sum(a, -b, s, err);
}

// a == hi + lo with hi and lo holding at most 26 significant bits each
// (Veltkamp/Dekker split with 2^27 + 1); needs |a| < 2^996.
inline void split(double a, double& hi, double& lo) noexcept {
    constexpr double kSplitter = 134217729.0;  // 2^27 + 1
    const double c = kSplitter * a;
    const double big = c - a;
    hi = c - big;
    lo = a - hi;
}

// p + err == a * b exactly, p = fl(a * b).
inline void two_product(double a, double b, double& p, double& err) noexcept {
    p = a * b;
#if defined(FP_FAST_FMA)
    err = std::fma(a, b, -p);  // explicit fma: exact, and not a contraction
#else
    // Dekker: the four partial products of the halves are exact.
    double a_hi, a_lo, b_hi, b_lo;
    split(a, a_hi, a_lo);
    split(b, b_hi, b_lo);
    const double e1 = p - a_hi * b_hi;
    const double e2 = e1 - a_lo * b_hi;
    const double e3 = e2 - a_hi * b_lo;
    err = a_lo * b_lo - e3;
#endif
}

// ---- expansion operations on raw arrays (expansion.cpp) ------------------
// Inputs have length >= 1; h must not alias the inputs and must hold the
// worst-case length given with each function. Each returns the length of h
// (>= 1).

// h = e + f, or e - f when negate_f; h holds elen + flen components.
int sum_zeroelim(int elen, const double* e, int flen, const double* f, bool negate_f,
                 double* h) noexcept;

// h = b * e; h holds 2 * elen components.
int scale_zeroelim(int elen, const double* e, double b, double* h) noexcept;

// Rewrites e in place as a nonadjacent expansion of the same value with
// fewer components (Shewchuk's Compress, Theorem 23); returns its length.
// Lengths otherwise only grow with each operation, so compressing the
// intermediate results of long formulas keeps the later steps short.
int compress(int elen, double* e) noexcept;

// ---- fixed-capacity value type -------------------------------------------

template <int N>
struct Expansion {
    static_assert(N >= 1, "an expansion has at least one component");
    int n = 0;    // number of components in use, 1..N once built
    double c[N];  // components, increasing magnitude; left uninitialised

    int sign() const noexcept {
        const double top = c[n - 1];
        return (top > 0.0) - (top < 0.0);
    }
};

template <int N>
void compress(Expansion<N>& e) noexcept {
    e.n = compress(e.n, e.c);
}

template <int N>
Expansion<N> compressed(Expansion<N> e) noexcept {
    compress(e);
    return e;
}

inline Expansion<1> exact(double a) noexcept {
    Expansion<1> r;
    r.n = 1;
    r.c[0] = a;
    return r;
}

// Builds the two-component expansion hi + lo (|lo| <= ulp(hi)/2), dropping
// a zero lo.
inline Expansion<2> from_pair(double hi, double lo) noexcept {
    Expansion<2> r;
    if (lo != 0.0) {
        r.n = 2;
        r.c[0] = lo;
        r.c[1] = hi;
    } else {
        r.n = 1;
        r.c[0] = hi;
    }
    return r;
}

// Exact a * b.
inline Expansion<2> product(double a, double b) noexcept {
    double p, err;
    two_product(a, b, p, err);
    return from_pair(p, err);
}

// Exact a - b.
inline Expansion<2> difference(double a, double b) noexcept {
    double s, err;
    two_diff(a, b, s, err);
    return from_pair(s, err);
}

template <int A, int B>
Expansion<A + B> operator+(const Expansion<A>& e, const Expansion<B>& f) noexcept {
    Expansion<A + B> h;
    h.n = sum_zeroelim(e.n, e.c, f.n, f.c, false, h.c);
    return h;
}

template <int A, int B>
Expansion<A + B> operator-(const Expansion<A>& e, const Expansion<B>& f) noexcept {
    Expansion<A + B> h;
    h.n = sum_zeroelim(e.n, e.c, f.n, f.c, true, h.c);
    return h;
}

template <int A>
Expansion<A> operator-(const Expansion<A>& e) noexcept {
    Expansion<A> h;
    h.n = e.n;
    for (int i = 0; i < e.n; ++i) h.c[i] = -e.c[i];
    return h;
}

template <int A>
Expansion<2 * A> operator*(double b, const Expansion<A>& e) noexcept {
    Expansion<2 * A> h;
    h.n = scale_zeroelim(e.n, e.c, b, h.c);
    return h;
}

// Exact a*b - c*d (a 2x2 minor).
inline Expansion<4> minor2(double a, double b, double c, double d) noexcept {
    return product(a, b) - product(c, d);
}

}  // namespace cbr::geom::xp

// Expansion sum, scale and compression (see expansion.hpp).
//
// They follow the algorithms proved in Shewchuk 1997 (Fast-Expansion-Sum,
// Theorem 13; Scale-Expansion, Theorem 19; Compress, Theorem 23): with
// round-to-nearest-even and strongly nonoverlapping inputs, the outputs are
// strongly nonoverlapping (Compress: nonadjacent, which is stronger)
// expansions of the exact result. Dropping zero components keeps that
// property and keeps the expansions short.
#include "geom/expansion.hpp"

namespace cbr::geom::xp {
namespace {

// The components of e and (+/-) f, merged by increasing magnitude.
class MergedComponents {
public:
    MergedComponents(int elen, const double* e, int flen, const double* f, bool negate_f) noexcept
        : e_(e), f_(f), elen_(elen), flen_(flen), f_sign_(negate_f ? -1.0 : 1.0) {}

    bool done() const noexcept { return i_ == elen_ && j_ == flen_; }

    double next() noexcept {
        if (j_ == flen_ || (i_ < elen_ && std::fabs(e_[i_]) <= std::fabs(f_[j_]))) {
            return e_[i_++];
        }
        return f_sign_ * f_[j_++];
    }

private:
    const double* e_;
    const double* f_;
    int elen_;
    int flen_;
    double f_sign_;
    int i_ = 0;
    int j_ = 0;
};

// two_product(a, b) for a fixed b, splitting b only once.
class ScaledBy {
public:
    explicit ScaledBy(double b) noexcept : b_(b) { split(b, b_hi_, b_lo_); }

    void two_product(double a, double& p, double& err) const noexcept {
        p = a * b_;
#if defined(FP_FAST_FMA)
        err = std::fma(a, b_, -p);
#else
        double a_hi, a_lo;
        split(a, a_hi, a_lo);
        const double e1 = p - a_hi * b_hi_;
        const double e2 = e1 - a_lo * b_hi_;
        const double e3 = e2 - a_hi * b_lo_;
        err = a_lo * b_lo_ - e3;
#endif
    }

private:
    double b_;
    double b_hi_;
    double b_lo_;
};

}  // namespace

int sum_zeroelim(int elen, const double* e, int flen, const double* f, bool negate_f,
                 double* h) noexcept {
    MergedComponents g(elen, e, flen, f, negate_f);
    int hlen = 0;
    double q = g.next();
    double s;
    double err;
    // The second component is at least as large as the first: fast two-sum.
    if (!g.done()) {
        fast_two_sum(g.next(), q, s, err);
        q = s;
        if (err != 0.0) h[hlen++] = err;
    }
    // Afterwards q may exceed the next component: full two-sum.
    while (!g.done()) {
        two_sum(q, g.next(), s, err);
        q = s;
        if (err != 0.0) h[hlen++] = err;
    }
    if (q != 0.0 || hlen == 0) h[hlen++] = q;
    return hlen;
}

int scale_zeroelim(int elen, const double* e, double b, double* h) noexcept {
    if (b == 0.0) {
        h[0] = 0.0;
        return 1;
    }
    const ScaledBy times_b(b);
    int hlen = 0;
    double q;
    double err;
    times_b.two_product(e[0], q, err);
    if (err != 0.0) h[hlen++] = err;
    for (int i = 1; i < elen; ++i) {
        double p_hi;
        double p_lo;
        times_b.two_product(e[i], p_hi, p_lo);
        double s;
        two_sum(q, p_lo, s, err);
        if (err != 0.0) h[hlen++] = err;
        fast_two_sum(p_hi, s, q, err);  // |p_hi| >= |s| (Shewchuk, Thm. 19)
        if (err != 0.0) h[hlen++] = err;
    }
    if (q != 0.0 || hlen == 0) h[hlen++] = q;
    return hlen;
}

int compress(int elen, double* e) noexcept {
    // Top-down: accumulate from the largest component; whenever the sum
    // cannot absorb the next component exactly, store the sum (it goes to
    // the slots already read, from the top) and restart from the roundoff.
    int bottom = elen - 1;
    double q = e[elen - 1];
    for (int i = elen - 2; i >= 0; --i) {
        double s, err;
        fast_two_sum(q, e[i], s, err);
        if (err != 0.0) {
            e[bottom--] = s;
            q = err;
        } else {
            q = s;
        }
    }
    e[bottom] = q;  // e[bottom..elen-1]: increasing magnitude
    // Bottom-up: carry the small components into the larger ones, emitting
    // the roundoffs (to slots already read, from the bottom).
    int top = 0;
    for (int i = bottom + 1; i < elen; ++i) {
        double s, err;
        fast_two_sum(e[i], q, s, err);
        if (err != 0.0) e[top++] = err;
        q = s;
    }
    e[top++] = q;
    return top;
}

}  // namespace cbr::geom::xp

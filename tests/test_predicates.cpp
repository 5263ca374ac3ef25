// Exact predicates (geom/predicates) against exact rational arithmetic (GMP).
//
// References are evaluated independently of the implementation: plain
// Gaussian elimination on mpq_class matrices built from the definitions
// (det[b-a, c-a, d-a]; -det[1, p, |p|^2]; the same with |p|^2 + eps^k(p)
// for an explicit eps small enough for the inputs). Inputs: random points,
// points nudged by a few ulps off planes / spheres / circles, exactly
// degenerate grids and integer cospherical / cocircular sets (also in tilted
// planes), and mixtures of huge and tiny coordinates up to the supported
// range 1e+-40. The exact stages are also called directly, so that they are
// checked on inputs the filter would otherwise decide.
#include <doctest/doctest.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <vector>

#include "geom/plane_side.hpp"
#include "geom/predicates.hpp"

namespace {

using cbr::geom::PredicateCounters;
using Point = std::array<double, 3>;

// ---- rational references ---------------------------------------------------

// Determinant of an n x n row-major rational matrix (Gaussian elimination).
mpq_class det(std::vector<mpq_class> m, int n) {
    mpq_class result = 1;
    for (int col = 0; col < n; ++col) {
        int pivot = col;
        while (pivot < n && sgn(m[pivot * n + col]) == 0) ++pivot;
        if (pivot == n) return 0;
        if (pivot != col) {
            for (int k = 0; k < n; ++k) std::swap(m[pivot * n + k], m[col * n + k]);
            result = -result;
        }
        result *= m[col * n + col];
        for (int r = col + 1; r < n; ++r) {
            if (sgn(m[r * n + col]) == 0) continue;
            const mpq_class f = m[r * n + col] / m[col * n + col];
            for (int k = col; k < n; ++k) m[r * n + k] -= f * m[col * n + k];
        }
    }
    return result;
}

mpq_class lift(const Point& p) {
    const mpq_class x(p[0]), y(p[1]), z(p[2]);
    return x * x + y * y + z * z;
}

int ref_orient3d(const Point& a, const Point& b, const Point& c, const Point& d) {
    std::vector<mpq_class> m;
    for (const Point* p : {&b, &c, &d}) {
        for (int k = 0; k < 3; ++k) m.push_back(mpq_class((*p)[k]) - mpq_class(a[k]));
    }
    return sgn(det(m, 3));
}

// Sign of -det[1, p, |p|^2 + perturbation(p)] over the five rows.
int ref_lifted(const std::array<Point, 5>& p, const std::array<mpq_class, 5>& perturbation) {
    std::vector<mpq_class> m;
    for (int i = 0; i < 5; ++i) {
        m.push_back(1);
        for (int k = 0; k < 3; ++k) m.push_back(mpq_class(p[i][k]));
        m.push_back(lift(p[i]) + perturbation[i]);
    }
    return -sgn(det(m, 5));
}

int ref_insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
    return ref_lifted({a, b, c, d, e}, {0, 0, 0, 0, 0});
}

// An eps for which the sign of D(eps) = D0 + sum_k eps^k T_k is the sign of
// its first non-zero coefficient. With every coordinate a multiple of 2^-g
// and below 2^M in magnitude: a non-zero D0 (degree 5) is >= 2^-5g, a
// non-zero cofactor T_k (4x4 det[1, p], degree 3) is >= 2^-3g, and
// |T_k| < 6 (2^(M+1))^3 < 2^(3M+6). So any eps < 2^-(5g + 3M + 9) works.
mpq_class safe_eps(const std::array<Point, 5>& p) {
    long g = 0;
    int mag = 0;
    for (const Point& q : p) {
        for (double x : q) {
            if (x == 0.0) continue;
            const mpq_class r(x);
            g = std::max<long>(g, static_cast<long>(mpz_sizeinbase(r.get_den().get_mpz_t(), 2)) - 1);
            int e;
            std::frexp(x, &e);
            mag = std::max(mag, e);
        }
    }
    mpz_class den;
    mpz_ui_pow_ui(den.get_mpz_t(), 2, static_cast<unsigned long>(5 * g + 3 * mag + 12));
    return mpq_class(mpz_class(1), den);
}

int lex_cmp(const Point& p, const Point& q) {
    return p < q ? -1 : (q < p ? 1 : 0);  // std::array compares lexicographically
}

// insphere_sos by definition: the lexicographically smallest point gets eps^1.
int ref_insphere_sos(const Point& a, const Point& b, const Point& c, const Point& d,
                     const Point& e) {
    const std::array<Point, 5> p = {a, b, c, d, e};
    const mpq_class eps = safe_eps(p);
    std::array<mpq_class, 5> perturbation;
    for (int i = 0; i < 5; ++i) {
        int rank = 0;
        for (int j = 0; j < 5; ++j) rank += lex_cmp(p[j], p[i]) < 0;
        perturbation[i] = 1;
        for (int k = 0; k <= rank; ++k) perturbation[i] *= eps;
    }
    return ref_lifted(p, perturbation);
}

bool ref_collinear(const Point& a, const Point& b, const Point& c) {
    mpq_class u[3], v[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = mpq_class(b[k]) - mpq_class(a[k]);
        v[k] = mpq_class(c[k]) - mpq_class(a[k]);
    }
    return sgn(u[1] * v[2] - u[2] * v[1]) == 0 && sgn(u[2] * v[0] - u[0] * v[2]) == 0 &&
           sgn(u[0] * v[1] - u[1] * v[0]) == 0;
}

// ---- calls through arrays ---------------------------------------------------

int orient3d(const Point& a, const Point& b, const Point& c, const Point& d,
             PredicateCounters* k = nullptr) {
    return cbr::geom::orient3d(a.data(), b.data(), c.data(), d.data(), k);
}
int insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e,
             PredicateCounters* k = nullptr) {
    return cbr::geom::insphere(a.data(), b.data(), c.data(), d.data(), e.data(), k);
}
int insphere_sos(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e,
                 PredicateCounters* k = nullptr) {
    return cbr::geom::insphere_sos(a.data(), b.data(), c.data(), d.data(), e.data(), k);
}
int incircle(const Point& a, const Point& b, const Point& c, const Point& p,
             PredicateCounters* k = nullptr) {
    return cbr::geom::incircle_coplanar_sos(a.data(), b.data(), c.data(), p.data(), k);
}

// ---- input generators ---------------------------------------------------------

class Rng {
public:
    explicit Rng(std::uint64_t seed) : g_(seed) {}
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * (static_cast<double>(g_() >> 11) * 0x1p-53);
    }
    // Like uniform, but with full 53-bit significands at every magnitude
    // (uniform's values share one coarse grid, so their differences would
    // all be exact and miss the general exact path).
    double full(double lo, double hi) { return uniform(lo, hi) * 0.7071067811865476; }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(g_); }
    Point point(double lo, double hi) { return {full(lo, hi), full(lo, hi), full(lo, hi)}; }
    template <class T>
    const T& pick(const std::vector<T>& v) {
        return v[static_cast<std::size_t>(integer(0, static_cast<int>(v.size()) - 1))];
    }

private:
    std::mt19937_64 g_;
};

// x moved by `steps` ulps (towards +inf when steps > 0); 0 moves to
// steps * 1e-40 instead (subnormals are outside the supported range).
double nudge(double x, int steps) {
    if (x == 0.0) return steps * cbr::geom::kMinMagnitude;
    const double target = steps > 0 ? std::numeric_limits<double>::infinity()
                                    : -std::numeric_limits<double>::infinity();
    for (int i = 0; i < std::abs(steps); ++i) x = std::nextafter(x, target);
    return x;
}

Point nudged(Point p, int axis, int steps) {
    p[static_cast<std::size_t>(axis)] = nudge(p[static_cast<std::size_t>(axis)], steps);
    return p;
}

// Integer points with x^2 + y^2 + z^2 == r2 (cospherical).
std::vector<Point> integer_sphere(int r2) {
    std::vector<Point> out;
    const int r = static_cast<int>(std::sqrt(double(r2))) + 1;
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            for (int z = -r; z <= r; ++z)
                if (x * x + y * y + z * z == r2) out.push_back({double(x), double(y), double(z)});
    return out;
}

std::vector<Point> grid(int n, double spacing, double offset) {
    std::vector<Point> out;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k)
                out.push_back({offset + i * spacing, offset + j * spacing, offset + k * spacing});
    return out;
}

std::vector<Point> cube_corners(double lo, double hi) {
    std::vector<Point> out;
    for (int i = 0; i < 8; ++i) out.push_back({i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo});
    return out;
}

// Coordinates that mix huge and tiny magnitudes, up to the range limits.
std::vector<double> extreme_values() {
    std::vector<double> v = {0.0, 1.0, -1.5, 3.0};
    for (double base : {1e20, 1e-20, 1e40, 1e-40, 7.5e39, 2.5e-40, 1e10, 1e-10}) {
        for (int k = -2; k <= 2; ++k) {
            const double x = nudge(base, k);
            if (std::fabs(x) >= 1e-40 && std::fabs(x) <= 1e40) {
                v.push_back(x);
                v.push_back(-x);
            }
        }
    }
    return v;
}

Point extreme_point(Rng& rng, const std::vector<double>& values) {
    return {rng.pick(values), rng.pick(values), rng.pick(values)};
}

Point transformed(const Point& p, double scale, double offset) {
    return {p[0] * scale + offset, p[1] * scale + offset, p[2] * scale + offset};
}

// ---- checking helpers ---------------------------------------------------------

// orient3d and its exact stages, against the rational reference.
void check_orient3d(const Point& a, const Point& b, const Point& c, const Point& d) {
    const int ref = ref_orient3d(a, b, c, d);
    CHECK(orient3d(a, b, c, d) == ref);
    CHECK(cbr::geom::detail::orient3d_exact(a.data(), b.data(), c.data(), d.data(), nullptr) == ref);
    CHECK(cbr::geom::detail::orient3d_exact_raw(a.data(), b.data(), c.data(), d.data()) == ref);
    cbr::geom::PlaneSide side(a.data(), b.data(), c.data());
    CHECK(side(d.data()) == ref);
}

void check_insphere(const Point& a, const Point& b, const Point& c, const Point& d,
                    const Point& e) {
    const int ref = ref_insphere(a, b, c, d, e);
    CHECK(insphere(a, b, c, d, e) == ref);
    CHECK(cbr::geom::detail::insphere_exact(a.data(), b.data(), c.data(), d.data(), e.data(),
                                            nullptr) == ref);
    CHECK(cbr::geom::detail::insphere_exact_raw(a.data(), b.data(), c.data(), d.data(),
                                                e.data()) == ref);
}

bool distinct(const std::vector<const Point*>& pts) {
    for (std::size_t i = 0; i < pts.size(); ++i)
        for (std::size_t j = i + 1; j < pts.size(); ++j)
            if (*pts[i] == *pts[j]) return false;
    return true;
}

void check_insphere_sos(const Point& a, const Point& b, const Point& c, const Point& d,
                        const Point& e) {
    const int got = insphere_sos(a, b, c, d, e);
    CHECK(got == ref_insphere_sos(a, b, c, d, e));
    const int plain = ref_insphere(a, b, c, d, e);
    if (plain != 0) CHECK(got == plain);
    if (distinct({&a, &b, &c, &d, &e}) && ref_orient3d(a, b, c, d) != 0) CHECK(got != 0);
}

template <class F>
void for_random_tuples(Rng& rng, const std::vector<Point>& pts, int count, int arity, F f) {
    std::vector<const Point*> t(static_cast<std::size_t>(arity));
    for (int n = 0; n < count; ++n) {
        for (auto& p : t) p = &rng.pick(pts);
        f(t);
    }
}

}  // namespace

// ============================================================================
// orient3d
// ============================================================================

TEST_CASE("orient3d: sign convention") {
    const Point o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
    CHECK(orient3d(o, x, y, z) == 1);  // z on the side of x cross y
    CHECK(orient3d(o, y, x, z) == -1);
    CHECK(orient3d(o, x, y, Point{0, 0, -1}) == -1);
    CHECK(orient3d(o, x, y, Point{3, -7, 0}) == 0);
    CHECK(orient3d(o, o, y, z) == 0);
}

TEST_CASE("orient3d: two equal points give 0, whichever two") {
    // The exact stage answers these without its expansions; a copy (equal
    // values, another address) and the same pointer must both give 0, and
    // -0.0 equals 0.0.
    Rng rng(11);
    for (int n = 0; n < 200; ++n) {
        const double s = std::ldexp(1.0, rng.integer(-40, 40));
        Point p[4] = {rng.point(-s, s), rng.point(-s, s), rng.point(-s, s), rng.point(-s, s)};
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                Point q[4] = {p[0], p[1], p[2], p[3]};
                q[j] = q[i];
                CHECK(orient3d(q[0], q[1], q[2], q[3]) == 0);
                const double* r[4] = {q[0].data(), q[1].data(), q[2].data(), q[3].data()};
                r[j] = r[i];
                CHECK(cbr::geom::orient3d(r[0], r[1], r[2], r[3]) == 0);
            }
    }
    const Point zero{0, 0, 0}, negative_zero{-0.0, 0, -0.0}, x{1, 0, 0}, y{0, 1, 0};
    CHECK(orient3d(zero, x, y, negative_zero) == 0);
}

TEST_CASE("orient3d: four points on an axis-parallel plane give 0, one ulp off the plane does not") {
    // The exact stage answers a shared coordinate without its expansions
    // (the flat faces of CAD parts, like the feeder body's caps at
    // z = 4.5001893): non-dyadic coordinates, so that nothing else in the
    // exact stage is exact in doubles.
    Rng rng(13);
    int nonzero = 0;
    for (int n = 0; n < 300; ++n) {
        const double s = std::ldexp(1.0, rng.integer(-20, 20));
        const double level = rng.uniform(-s, s);
        const int axis = rng.integer(0, 2);
        Point p[4];
        for (Point& q : p) {
            q = rng.point(-s, s);
            q[static_cast<std::size_t>(axis)] = level;
        }
        CHECK(orient3d(p[0], p[1], p[2], p[3]) == 0);
        CHECK(cbr::geom::detail::orient3d_exact(p[0].data(), p[1].data(), p[2].data(), p[3].data(), nullptr) == 0);
        const int moved = rng.integer(0, 3);
        p[moved] = nudged(p[moved], axis, rng.integer(0, 1) ? 1 : -1);
        check_orient3d(p[0], p[1], p[2], p[3]);
        nonzero += ref_orient3d(p[0], p[1], p[2], p[3]) != 0;
    }
    CHECK(nonzero == 300);  // off the plane is off it (unless abc were collinear)
}

TEST_CASE("orient3d: integer and dyadic points (the exact stage in doubles, and its way out)") {
    // Up to 2^12 every step of the determinant is exact in doubles; up to
    // 2^26 the minors are but their products by z need not be, and the
    // exact stage must notice and fall back to expansions. Points on or
    // next to a plane make the filter give up, so the exact stage decides.
    Rng rng(12);
    for (const int bits : {4, 12, 20, 26}) {
        const double top = std::ldexp(1.0, bits);
        for (int n = 0; n < 400; ++n) {
            auto integer_point = [&] {
                return Point{std::round(rng.uniform(-top, top)), std::round(rng.uniform(-top, top)),
                             std::round(rng.uniform(-top, top))};
            };
            const Point a = integer_point(), b = integer_point(), c = integer_point();
            const int s = rng.integer(-3, 3), t = rng.integer(-3, 3);
            Point d;  // on the plane of abc (integer combination), then moved by -1, 0 or 1
            for (int k = 0; k < 3; ++k) d[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
            d[static_cast<std::size_t>(rng.integer(0, 2))] += rng.integer(-1, 1);
            check_orient3d(a, b, c, d);
            const double scale = std::ldexp(1.0, rng.integer(-60, 60));  // dyadic: same bits
            auto scaled = [&](const Point& p) { return Point{p[0] * scale, p[1] * scale, p[2] * scale}; };
            check_orient3d(scaled(a), scaled(b), scaled(c), scaled(d));
        }
    }
}

// Three rows of integers in [-top, top], all scaled by one random power of
// two; with `in_plane` the third is r0 - 2 r1 (a zero determinant: the
// third lies in the plane of the first two).
std::array<Point, 3> scaled_integer_rows(Rng& rng, double top, bool in_plane) {
    std::array<Point, 3> r;
    for (Point& p : r)
        for (double& x : p) x = std::round(rng.uniform(-top, top));
    if (in_plane)
        for (int k = 0; k < 3; ++k) r[2][k] = r[0][k] - 2 * r[1][k];
    const double scale = std::ldexp(1.0, rng.integer(-40, 40));
    for (Point& p : r)
        for (double& x : p) x *= scale;
    return r;
}

// One in-doubles evaluation by Dekker's split and by the fma: both must
// accept or refuse together, agree on the value, and (accepted) give
// orient3d's sign of the rows r. Counts the outcome in exact or refused.
void check_split_and_fma(bool split_ok, bool fma_ok, double by_split, double by_fma, const std::array<Point, 3>& r,
                         int& exact, int& refused) {
    CHECK(split_ok == fma_ok);
    if (!split_ok) {
        ++refused;
        return;
    }
    ++exact;
    CHECK(by_split == by_fma);
    const int sign = (by_split > 0) - (by_split < 0);
    CHECK(sign == ref_orient3d(Point{0, 0, 0}, r[0], r[1], r[2]));
}

TEST_CASE("det3_in_doubles: Dekker's and the fused multiply-add's checks agree, and with GMP") {
    // The exact stage's shortcut checks each product by its error term:
    // Dekker's split everywhere, one fma where the processor has one (the
    // run-time choice would leave the other untested on any one machine).
    // Integers of up to 2^12 make every step exact; up to 2^26 the minors
    // are but their products by the third column need not be, and both
    // checks must say so together.
    Rng rng(14);
    const bool fma = cbr::geom::detail::fma_available();
    int exact = 0, refused = 0;
    for (const int bits : {4, 12, 20, 26}) {
        const double top = std::ldexp(1.0, bits);
        for (int n = 0; n < 400; ++n) {
            const std::array<Point, 3> r = scaled_integer_rows(rng, top, n % 2 == 0);
            double by_split = 0, by_fma = 0;
            const bool split_ok = cbr::geom::detail::det3_in_doubles(r[0].data(), r[1].data(), r[2].data(), by_split, false);
            const bool fma_ok = cbr::geom::detail::det3_in_doubles(r[0].data(), r[1].data(), r[2].data(), by_fma, fma);
            check_split_and_fma(split_ok, fma_ok, by_split, by_fma, r, exact, refused);
        }
    }
    CHECK(exact > 400);  // both kinds were met
    CHECK(refused > 100);
}

TEST_CASE("normal_in_doubles and dot_in_doubles: Dekker's and the fused multiply-add's checks agree, and with GMP") {
    // PlaneSide's exact stage: the plane's normal u x v, then w . n, each in
    // doubles when every step is exact; the sign of the dot product is then
    // orient3d's. Same bit sizes as for det3_in_doubles.
    Rng rng(15);
    const bool fma = cbr::geom::detail::fma_available();
    int exact = 0, refused = 0;
    for (const int bits : {4, 12, 20, 26}) {
        const double top = std::ldexp(1.0, bits);
        for (int n = 0; n < 400; ++n) {
            const std::array<Point, 3> r = scaled_integer_rows(rng, top, n % 2 == 0);
            double n_split[3], n_fma[3];
            const bool split_ok = cbr::geom::detail::normal_in_doubles(r[0].data(), r[1].data(), n_split, false);
            const bool fma_ok = cbr::geom::detail::normal_in_doubles(r[0].data(), r[1].data(), n_fma, fma);
            CHECK(split_ok == fma_ok);
            if (!split_ok) {
                ++refused;
                continue;
            }
            for (int k = 0; k < 3; ++k) CHECK(n_split[k] == n_fma[k]);
            double by_split = 0, by_fma = 0;
            const bool dot_split_ok = cbr::geom::detail::dot_in_doubles(r[2].data(), n_split, by_split, false);
            const bool dot_fma_ok = cbr::geom::detail::dot_in_doubles(r[2].data(), n_split, by_fma, fma);
            check_split_and_fma(dot_split_ok, dot_fma_ok, by_split, by_fma, r, exact, refused);
        }
    }
    CHECK(exact > 400);  // both kinds were met
    CHECK(refused > 100);
    // Steps whose rounding would change the answer must be refused.
    // (2^27 + 1)(2^26 + 1) = 2^53 + 2^27 + 2^26 + 1 rounds to X = 2^53 +
    // 2^27 + 2^26: w . n below is exactly 1, and 0 with that product rounded.
    const double X = std::ldexp(1.0, 53) + std::ldexp(1.0, 27) + std::ldexp(1.0, 26);
    const double n[3] = {1, 0, std::ldexp(1.0, 27) + 1};
    const double w[3] = {-X, 0, std::ldexp(1.0, 26) + 1};
    // 2^60 - 1, the z component of u x v here, is no double.
    const double u[3] = {std::ldexp(1.0, 30), 1, 0};
    const double v[3] = {1, std::ldexp(1.0, 30), 0};
    // and (2^27 + 1)(2^26 + 1), the z component of p x q, no double either.
    const double p[3] = {std::ldexp(1.0, 27) + 1, 0, 0};
    const double q[3] = {0, std::ldexp(1.0, 26) + 1, 0};
    for (const bool use_fma : {false, fma}) {
        double dot = 0, normal[3];
        CHECK_FALSE(cbr::geom::detail::dot_in_doubles(w, n, dot, use_fma));
        CHECK_FALSE(cbr::geom::detail::normal_in_doubles(u, v, normal, use_fma));
        CHECK_FALSE(cbr::geom::detail::normal_in_doubles(p, q, normal, use_fma));
    }
}

TEST_CASE("orient3d: random points") {
    Rng rng(1);
    for (int n = 0; n < 3000; ++n) {
        const double s = std::ldexp(1.0, rng.integer(-30, 30));
        check_orient3d(rng.point(-s, s), rng.point(-s, s), rng.point(-s, s), rng.point(-s, s));
    }
}

TEST_CASE("orient3d: points a few ulps off a plane") {
    Rng rng(2);
    for (int n = 0; n < 300; ++n) {
        const Point a = rng.point(-1, 1), b = rng.point(-1, 1), c = rng.point(-1, 1);
        const double s = rng.uniform(-2, 3), t = rng.uniform(-2, 3);
        Point d;
        for (int k = 0; k < 3; ++k) d[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
        for (int axis = 0; axis < 3; ++axis) {
            for (int steps = -3; steps <= 3; ++steps) check_orient3d(a, b, c, nudged(d, axis, steps));
        }
    }
    // Far from the origin: coordinates 1e20 + k ulps.
    for (int n = 0; n < 300; ++n) {
        const double big = 1e20;
        auto p = [&] { return Point{nudge(big, rng.integer(-4, 4)), nudge(big, rng.integer(-4, 4)),
                                    nudge(big, rng.integer(-4, 4))}; };
        check_orient3d(p(), p(), p(), p());
    }
}

TEST_CASE("orient3d: exactly coplanar grids and planes") {
    Rng rng(3);
    const auto g = grid(4, 1.0, 0.0);
    const auto g2 = grid(4, 0.1, -0.15);  // non-dyadic spacing: inexact differences
    const auto g3 = grid(3, 1e-30, 1e-20);
    int zeros = 0;
    for (const auto* pts : {&g, &g2, &g3}) {
        for_random_tuples(rng, *pts, 1500, 4, [&](const std::vector<const Point*>& t) {
            check_orient3d(*t[0], *t[1], *t[2], *t[3]);
            zeros += ref_orient3d(*t[0], *t[1], *t[2], *t[3]) == 0;
        });
    }
    CHECK(zeros > 1000);  // the test does exercise degenerate cases
    // Integer points of the tilted plane x + 2y - 3z = 5.
    std::vector<Point> plane;
    for (int y = -6; y <= 6; ++y)
        for (int z = -6; z <= 6; ++z) plane.push_back({double(5 - 2 * y + 3 * z), double(y), double(z)});
    for_random_tuples(rng, plane, 1000, 4, [&](const std::vector<const Point*>& t) {
        CHECK(orient3d(*t[0], *t[1], *t[2], *t[3]) == 0);
        check_orient3d(*t[0], *t[1], *t[2], nudged(*t[3], rng.integer(0, 2), rng.integer(-2, 2)));
    });
}

// PlaneSide keeps the plane's exact normal from one point to the next:
// many points against one plane, exactly on it or a few ulps off, with
// representable differences or not (non-dyadic grid, mixed magnitudes).
TEST_CASE("orient3d: PlaneSide against one plane for many points") {
    Rng rng(6);
    const auto g = grid(4, 1.0, 0.0);
    const auto g2 = grid(4, 0.1, -0.15);
    const auto values = extreme_values();
    int zeros = 0;
    for (int plane = 0; plane < 300; ++plane) {
        const std::vector<Point>& pts = plane % 2 ? g : g2;
        const int last = static_cast<int>(pts.size()) - 1;
        const auto any = [&] { return pts[static_cast<std::size_t>(rng.integer(0, last))]; };
        const Point a = any(), b = any();
        const Point c = plane % 5 == 0 ? extreme_point(rng, values) : any();
        cbr::geom::PlaneSide side(a.data(), b.data(), c.data());
        for (int n = 0; n < 40; ++n) {
            Point x = any();
            if (n % 3 == 0) x = nudged(x, rng.integer(0, 2), rng.integer(-2, 2));
            if (n % 7 == 0) x = extreme_point(rng, values);
            const int ref = ref_orient3d(a, b, c, x);
            CHECK(side(x.data()) == ref);
            zeros += ref == 0;
        }
    }
    CHECK(zeros > 1000);  // mostly points on the plane: the exact stage
}

TEST_CASE("orient3d: mixed magnitudes up to 1e+-40") {
    Rng rng(4);
    const auto values = extreme_values();
    for (int n = 0; n < 4000; ++n) {
        check_orient3d(extreme_point(rng, values), extreme_point(rng, values),
                       extreme_point(rng, values), extreme_point(rng, values));
    }
    // A tiny tetrahedron far away, and a huge one around a tiny offset.
    for (int n = 0; n < 500; ++n) {
        const double off = rng.pick(std::vector<double>{1e20, -1e30, 1e40 / 4});
        auto p = [&] { return Point{off + rng.integer(-3, 3) * 1e-20, nudge(off, rng.integer(-3, 3)),
                                    off * rng.integer(-1, 1) + rng.integer(-3, 3) * 1e-40}; };
        check_orient3d(p(), p(), p(), p());
    }
}

TEST_CASE("orient3d: permutations") {
    Rng rng(5);
    const auto g = grid(3, 1.0, 0.0);
    for_random_tuples(rng, g, 200, 4, [&](const std::vector<const Point*>& t) {
        std::array<int, 4> perm = {0, 1, 2, 3};
        const int base = orient3d(*t[0], *t[1], *t[2], *t[3]);
        int parity = 1;
        do {
            int inversions = 0;
            for (int i = 0; i < 4; ++i)
                for (int j = i + 1; j < 4; ++j) inversions += perm[i] > perm[j];
            parity = inversions % 2 == 0 ? 1 : -1;
            CHECK(orient3d(*t[perm[0]], *t[perm[1]], *t[perm[2]], *t[perm[3]]) == parity * base);
        } while (std::next_permutation(perm.begin(), perm.end()));
    });
}

// ============================================================================
// insphere
// ============================================================================

TEST_CASE("insphere: semantics") {
    const Point o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
    REQUIRE(orient3d(o, x, y, z) == 1);
    CHECK(insphere(o, x, y, z, Point{0.25, 0.25, 0.25}) == 1);
    CHECK(insphere(o, x, y, z, Point{2, 2, 2}) == -1);
    CHECK(insphere(o, x, y, z, Point{1, 1, 1}) == 0);  // the cube's corner is on the sphere
    CHECK(insphere(o, y, x, z, Point{0.25, 0.25, 0.25}) == -1);  // negative tetrahedron
    CHECK(insphere(o, y, x, z, Point{2, 2, 2}) == 1);
}

TEST_CASE("insphere: random points") {
    Rng rng(6);
    for (int n = 0; n < 2000; ++n) {
        const double s = std::ldexp(1.0, rng.integer(-30, 30));
        check_insphere(rng.point(-s, s), rng.point(-s, s), rng.point(-s, s), rng.point(-s, s),
                       rng.point(-s, s));
    }
}

TEST_CASE("insphere: cospherical and a few ulps off the sphere") {
    Rng rng(7);
    const auto sphere = integer_sphere(50);  // 42+ integer points
    REQUIRE(sphere.size() > 20);
    int zeros = 0;
    for (int n = 0; n < 1500; ++n) {
        const double scale = rng.pick(std::vector<double>{1.0, 0x1p-20, 0x1p30, 0.1, 3e-7});
        const double offset = rng.pick(std::vector<double>{0.0, 17.0, 0.3, -1e5});
        Point p[5];
        for (auto& q : p) q = transformed(rng.pick(sphere), scale, offset);
        zeros += ref_insphere(p[0], p[1], p[2], p[3], p[4]) == 0;
        check_insphere(p[0], p[1], p[2], p[3], p[4]);
        check_insphere(p[0], p[1], p[2], p[3], nudged(p[4], rng.integer(0, 2), rng.integer(-3, 3)));
    }
    CHECK(zeros > 300);
    // Points near a random sphere (rounded, so not exactly cospherical).
    for (int n = 0; n < 500; ++n) {
        const Point c = rng.point(-1, 1);
        const double r = rng.uniform(0.1, 2);
        Point p[5];
        for (auto& q : p) {
            const double th = rng.uniform(0, 6.283185307179586), ph = rng.uniform(-1.5, 1.5);
            q = {c[0] + r * std::cos(ph) * std::cos(th), c[1] + r * std::cos(ph) * std::sin(th),
                 c[2] + r * std::sin(ph)};
        }
        check_insphere(p[0], p[1], p[2], p[3], p[4]);
    }
}

TEST_CASE("insphere: degenerate grids and mixed magnitudes up to 1e+-40") {
    Rng rng(8);
    const auto g = grid(4, 1.0, 0.0);
    const auto g2 = grid(3, 0.1, -0.1);
    for (const auto* pts : {&g, &g2}) {
        for_random_tuples(rng, *pts, 800, 5, [&](const std::vector<const Point*>& t) {
            check_insphere(*t[0], *t[1], *t[2], *t[3], *t[4]);
        });
    }
    const auto values = extreme_values();
    for (int n = 0; n < 1500; ++n) {
        Point p[5];
        for (auto& q : p) q = extreme_point(rng, values);
        check_insphere(p[0], p[1], p[2], p[3], p[4]);
    }
    for (int n = 0; n < 300; ++n) {  // tiny cospherical set at a huge offset, and back
        const double scale = rng.pick(std::vector<double>{1e-20, 0x1p-100, 1e30});
        const double offset = rng.pick(std::vector<double>{1e20, 1e-30, -3e39});
        const auto sphere = integer_sphere(27);
        Point p[5];
        for (auto& q : p) q = transformed(rng.pick(sphere), scale, offset);
        check_insphere(p[0], p[1], p[2], p[3], p[4]);
    }
}

// ============================================================================
// insphere_sos
// ============================================================================

TEST_CASE("insphere_sos: explicit-eps rational determinant on degenerate sets") {
    Rng rng(9);
    const std::vector<std::vector<Point>> sets = {
        cube_corners(0, 1),    cube_corners(-0.1, 0.7), grid(3, 1.0, 0.0), grid(3, 0.1, 0.2),
        integer_sphere(50),    integer_sphere(27),      grid(3, 1e-30, 1e20),
    };
    for (const auto& pts : sets) {
        for_random_tuples(rng, pts, 500, 5, [&](const std::vector<const Point*>& t) {
            check_insphere_sos(*t[0], *t[1], *t[2], *t[3], *t[4]);
        });
    }
    const auto values = extreme_values();
    for (int n = 0; n < 200; ++n) {
        Point p[5];
        for (auto& q : p) q = extreme_point(rng, values);
        check_insphere_sos(p[0], p[1], p[2], p[3], p[4]);
    }
}

TEST_CASE("insphere_sos: never zero on valid cospherical inputs") {
    const auto sphere = integer_sphere(50);
    const std::size_t n = sphere.size();
    int checked = 0;
    for (std::size_t i = 0; i < n; i += 3)
        for (std::size_t j = i + 1; j < n; j += 2)
            for (std::size_t k = j + 1; k < n; k += 3)
                for (std::size_t l = k + 1; l < n; l += 5) {
                    const Point &a = sphere[i], &b = sphere[j], &c = sphere[k], &d = sphere[l];
                    if (orient3d(a, b, c, d) == 0) continue;
                    const Point& e = sphere[(i + j + k + l) % n];
                    if (e == a || e == b || e == c || e == d) continue;
                    REQUIRE(insphere(a, b, c, d, e) == 0);
                    CHECK(insphere_sos(a, b, c, d, e) != 0);
                    ++checked;
                }
    CHECK(checked > 100);
}

TEST_CASE("insphere_sos: even permutations of abcd keep the sign, odd ones flip it") {
    Rng rng(10);
    const auto corners = cube_corners(0, 1);
    const auto sphere = integer_sphere(27);
    for (const auto* pts : {&corners, &sphere}) {
        for_random_tuples(rng, *pts, 150, 5, [&](const std::vector<const Point*>& t) {
            std::array<int, 4> perm = {0, 1, 2, 3};
            const int base = insphere_sos(*t[0], *t[1], *t[2], *t[3], *t[4]);
            do {
                int inversions = 0;
                for (int i = 0; i < 4; ++i)
                    for (int j = i + 1; j < 4; ++j) inversions += perm[i] > perm[j];
                const int parity = inversions % 2 == 0 ? 1 : -1;
                CHECK(insphere_sos(*t[perm[0]], *t[perm[1]], *t[perm[2]], *t[perm[3]], *t[4]) ==
                      parity * base);
            } while (std::next_permutation(perm.begin(), perm.end()));
        });
    }
}

TEST_CASE("insphere_sos: coincident points give 0") {
    const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
    CHECK(insphere_sos(a, b, c, d, a) == 0);
    CHECK(insphere_sos(a, a, c, d, b) == 0);
}

// ============================================================================
// incircle_coplanar_sos
// ============================================================================

namespace {

// Points q with orient3d(a, b, c, q) > 0 (checked exactly), near and far.
std::vector<Point> positive_apexes(const Point& a, const Point& b, const Point& c, Rng& rng) {
    double n[3];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    std::vector<Point> out;
    const double size = std::max({std::fabs(u[0]), std::fabs(u[1]), std::fabs(u[2]),
                                  std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
    const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    auto keep_if_positive = [&](const Point& q) {
        if (ref_orient3d(a, b, c, q) > 0) out.push_back(q);
    };
    for (double t : {0.5, 3.0, 1e6}) {
        for (double side : {1.0, -1.0}) {
            Point q;
            if (norm > 0) {  // 0 when abc is almost (not exactly) collinear
                for (int k = 0; k < 3; ++k)
                    q[k] = a[k] + rng.uniform(-1, 1) * size + side * t * size * n[k] / norm;
                keep_if_positive(q);
            }
            for (int axis = 0; axis < 3; ++axis) {  // and along the axes
                q = a;
                q[static_cast<std::size_t>(axis)] += side * t * size;
                keep_if_positive(q);
            }
        }
    }
    return out;
}

// incircle_coplanar_sos(a, b, c, p) against insphere_sos(a, b, c, q, p) and
// its rational definition, for several q on the positive side.
void check_incircle(const Point& a, const Point& b, const Point& c, const Point& p, Rng& rng) {
    if (ref_collinear(a, b, c) || p == a || p == b || p == c) return;
    const int got = incircle(a, b, c, p);
    CHECK(got != 0);
    const auto apexes = positive_apexes(a, b, c, rng);
    CHECK(apexes.size() >= 2);
    for (const Point& q : apexes) {
        CHECK(got == insphere_sos(a, b, c, q, p));
        CHECK(got == ref_insphere_sos(a, b, c, q, p));
    }
}

// Points of `pts`, in groups of equal |p - center|^2 (cocircular when the
// points are coplanar).
std::vector<std::vector<Point>> cocircular_groups(const std::vector<Point>& pts) {
    std::map<double, std::vector<Point>> by_radius;
    for (const Point& p : pts) by_radius[p[0] * p[0] + p[1] * p[1] + p[2] * p[2]].push_back(p);
    std::vector<std::vector<Point>> out;
    for (auto& [r2, g] : by_radius)
        if (g.size() >= 4) out.push_back(g);
    return out;
}

// Integer points of the plane n . x = 0 within a box.
std::vector<Point> integer_plane(int nx, int ny, int nz, int r) {
    std::vector<Point> out;
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            for (int z = -r; z <= r; ++z)
                if (nx * x + ny * y + nz * z == 0) out.push_back({double(x), double(y), double(z)});
    return out;
}

}  // namespace

TEST_CASE("incircle_coplanar_sos: semantics") {
    Rng rng(11);
    const Point a{0, 0, 0}, b{4, 0, 0}, c{0, 4, 0};
    for (bool flip : {false, true}) {
        const Point& b2 = flip ? c : b;
        const Point& c2 = flip ? b : c;
        CHECK(incircle(a, b2, c2, Point{1, 1, 0}) == 1);
        CHECK(incircle(a, b2, c2, Point{5, 5, 0}) == -1);
        CHECK(incircle(a, b2, c2, Point{-1, -1, 0}) == -1);
        check_incircle(a, b2, c2, Point{4, 4, 0}, rng);  // cocircular: perturbed
    }
    // Square corners: of the two triangulations, the perturbation picks one.
    const Point s0{0, 0, 0}, s1{1, 0, 0}, s2{1, 1, 0}, s3{0, 1, 0};
    const int r1 = incircle(s0, s1, s2, s3), r2 = incircle(s0, s1, s3, s2);
    CHECK(r1 != 0);
    CHECK(r2 != 0);
    CHECK(incircle(Point{0, 0, 0}, Point{1, 1, 1}, Point{2, 2, 2}, Point{3, 0, 1}) == 0);  // collinear abc
}

TEST_CASE("incircle_coplanar_sos: cocircular integer sets in axis and tilted planes") {
    Rng rng(12);
    std::vector<std::vector<Point>> planes;
    // z = 0, z = 0.1, x = 3, y = -2: the circle x^2 + y^2 = 25 and a few others.
    std::vector<Point> z0, z01, x3, ym2;
    for (int i = -6; i <= 6; ++i)
        for (int j = -6; j <= 6; ++j) {
            if (i * i + j * j != 25 && i * i + j * j > 2 && i * i + j * j != 50) continue;
            z0.push_back({double(i), double(j), 0.0});
            z01.push_back({double(i) * 0.1, double(j) * 0.1, 0.1});
            x3.push_back({3.0, double(i), double(j)});
            ym2.push_back({double(j) * 1e20, -2.0, double(i) * 1e20});
        }
    planes = {z0, z01, x3, ym2};
    for (const auto& pts : planes) {
        for_random_tuples(rng, pts, 300, 4, [&](const std::vector<const Point*>& t) {
            check_incircle(*t[0], *t[1], *t[2], *t[3], rng);
        });
    }
    // Tilted planes through the origin: circles are sphere sections.
    int groups = 0;
    for (auto [nx, ny, nz] : {std::array<int, 3>{1, 1, 1}, {1, 2, 3}, {2, -1, 2}}) {
        const auto plane = integer_plane(nx, ny, nz, 7);
        for (const auto& g : cocircular_groups(plane)) {
            ++groups;
            for_random_tuples(rng, g, 40, 4, [&](const std::vector<const Point*>& t) {
                check_incircle(*t[0], *t[1], *t[2], *t[3], rng);
            });
            // Against any point of the plane too, also translated and scaled.
            for_random_tuples(rng, g, 20, 3, [&](const std::vector<const Point*>& t) {
                const Point& p = rng.pick(plane);
                check_incircle(*t[0], *t[1], *t[2], p, rng);
                const double s = 0x1p-20, o = 0x1p20;  // exact: stays coplanar
                check_incircle(transformed(*t[0], s, o), transformed(*t[1], s, o),
                               transformed(*t[2], s, o), transformed(p, s, o), rng);
            });
        }
    }
    CHECK(groups > 10);
}

TEST_CASE("incircle_coplanar_sos: random coplanar points and mixed magnitudes") {
    Rng rng(13);
    // Plane x = z with random doubles (exactly coplanar), and x + y = z with
    // dyadic coordinates of few bits (exact sums).
    for (int n = 0; n < 400; ++n) {
        Point p[4];
        for (auto& q : p) {
            const double s = rng.full(-1, 1), t = rng.full(-1, 1);
            q = {s, t, s};
        }
        check_incircle(p[0], p[1], p[2], p[3], rng);
        for (auto& q : p) {
            const double s = rng.integer(-1000, 1000) * 0x1p-8, t = rng.integer(-1000, 1000) * 0x1p-8;
            q = {s, t, s + t};
        }
        check_incircle(p[0], p[1], p[2], p[3], rng);
    }
    // Plane z = 1e-30 with coordinates mixing 1e20 + k ulps and 1e-20.
    const auto values = extreme_values();
    std::vector<double> xy;
    for (double v : values)
        if (std::fabs(v) <= 1e21) xy.push_back(v);
    for (int n = 0; n < 300; ++n) {
        Point p[4];
        for (auto& q : p) q = {rng.pick(xy), rng.pick(xy), 1e-30};
        check_incircle(p[0], p[1], p[2], p[3], rng);
    }
    const std::vector<std::array<int, 2>> circle = {{5, 0}, {3, 4}, {4, 3}, {0, 5}, {-3, 4},
                                                    {-5, 0}, {-4, -3}, {0, -5}, {4, -3}};
    // A few ulps off a circle, within the plane y = 0.5.
    for (int n = 0; n < 300; ++n) {
        Point p[4];
        for (auto& q : p) {
            const auto& c = rng.pick(circle);
            q = {double(c[0]), 0.5, double(c[1])};
        }
        check_incircle(p[0], p[1], p[2], nudged(p[3], 2 * rng.integer(0, 1), rng.integer(-3, 3)), rng);
    }
    // An integer circle, scaled, around a huge offset.
    for (int n = 0; n < 200; ++n) {
        Point p[4];
        for (auto& q : p) {
            const auto& c = rng.pick(circle);
            q = {1e20 + c[0] * 30000.0, 1e20, 1e20 + c[1] * 30000.0};  // rounded: near-cocircular
        }
        check_incircle(p[0], p[1], p[2], p[3], rng);
        for (auto& q : p) {
            const auto& c = rng.pick(circle);
            q = {0x1p60 + c[0] * 1024.0, 3.0, 0x1p60 + c[1] * 1024.0};  // exact: cocircular
        }
        check_incircle(p[0], p[1], p[2], p[3], rng);
    }
}

// ============================================================================
// collinear, lexicographic_compare, counters
// ============================================================================

TEST_CASE("collinear") {
    Rng rng(14);
    for (int n = 0; n < 2000; ++n) {
        const Point a = {double(rng.integer(-50, 50)), double(rng.integer(-50, 50)),
                         double(rng.integer(-50, 50))};
        const Point d = {double(rng.integer(-5, 5)), double(rng.integer(-5, 5)),
                         double(rng.integer(-5, 5))};
        const double s = rng.integer(-4, 4) * 0.1, t = rng.integer(-4, 4);
        const Point b = {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]};
        const Point c = {a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]};
        CHECK(cbr::geom::collinear(a.data(), b.data(), c.data()) == ref_collinear(a, b, c));
        const Point c2 = nudged(c, rng.integer(0, 2), rng.integer(-2, 2));
        CHECK(cbr::geom::collinear(a.data(), b.data(), c2.data()) == ref_collinear(a, b, c2));
        const Point big = {1e30 + t * 0x1p50, 1e-30, 1e20 + t * 0x1p20};
        CHECK(cbr::geom::collinear(a.data(), big.data(), c2.data()) == ref_collinear(a, big, c2));
    }
    const Point o{0, 0, 0}, p{1, 2, 3}, q{2, 4, 6}, r{2, 4, 6.000000000000001};
    CHECK(cbr::geom::collinear(o.data(), p.data(), q.data()));
    CHECK_FALSE(cbr::geom::collinear(o.data(), p.data(), r.data()));
    CHECK(cbr::geom::collinear(o.data(), o.data(), r.data()));
}

TEST_CASE("lexicographic_compare") {
    auto cmp = [](Point p, Point q) { return cbr::geom::lexicographic_compare(p.data(), q.data()); };
    CHECK(cmp({0, 0, 0}, {0, 0, 0}) == 0);
    CHECK(cmp({0.0, 0, 0}, {-0.0, 0, 0}) == 0);
    CHECK(cmp({1, 0, 0}, {0, 9, 9}) == 1);
    CHECK(cmp({0, 9, 9}, {1, 0, 0}) == -1);
    CHECK(cmp({1, 2, 0}, {1, 3, -5}) == -1);
    CHECK(cmp({1, 2, 4}, {1, 2, 3}) == 1);
    CHECK(cmp({1e-40, 2, 4}, {0, 2, 3}) == 1);
    CHECK(cmp({-1e40, 2, 4}, {nudge(-1e40, 1), 2, 3}) == -1);
    Rng rng(15);
    for (int n = 0; n < 1000; ++n) {
        const Point p = {double(rng.integer(0, 2)), double(rng.integer(0, 2)), double(rng.integer(0, 2))};
        const Point q = {double(rng.integer(0, 2)), double(rng.integer(0, 2)), double(rng.integer(0, 2))};
        CHECK(cmp(p, q) == lex_cmp(p, q));
        CHECK(cmp(q, p) == -cmp(p, q));
    }
}

TEST_CASE("counters count the exact and perturbed stages") {
    PredicateCounters k;
    const Point o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1}, xyz{1, 1, 1};
    CHECK(orient3d(o, x, y, z, &k) == 1);
    CHECK(insphere_sos(o, x, y, z, Point{0.2, 0.2, 0.2}, &k) == 1);
    CHECK(k.orient3d_exact == 0);
    CHECK(k.insphere_exact == 0);
    CHECK(orient3d(o, x, y, Point{1, 1, 0}, &k) == 0);
    CHECK(k.orient3d_exact == 1);
    CHECK(insphere(o, x, y, z, xyz, &k) == 0);
    CHECK(k.insphere_exact == 1);
    CHECK(k.insphere_perturbed == 0);
    CHECK(insphere_sos(o, x, y, z, xyz, &k) != 0);
    CHECK(k.insphere_exact == 2);
    CHECK(k.insphere_perturbed == 1);
    CHECK(incircle(o, x, Point{1, 1, 0}, y, &k) != 0);
    CHECK(k.insphere_exact == 3);
    CHECK(k.insphere_perturbed == 2);
}

// ============================================================================
// Micro-benchmark (skipped by default; run on a Release build with
//   test_predicates --no-skip --test-case="predicates benchmark").
// Tuples of distinct points, as the Delaunay kernel calls the predicates.
// ============================================================================

TEST_CASE("predicates benchmark" * doctest::skip()) {
    using Clock = std::chrono::steady_clock;
    constexpr int kCalls = 1'000'000;
    auto ns_per_call = [](Clock::time_point t0, Clock::time_point t1, int calls) {
        return std::chrono::duration<double, std::nano>(t1 - t0).count() / calls;
    };
    auto run = [&](const char* name, const std::vector<Point>& pts) {
        Rng rng(16);
        std::vector<const double*> tuples;  // 5 distinct points per call
        for (int n = 0; n < kCalls; ++n) {
            int idx[5];
            for (int j = 0; j < 5; ++j) {
                bool repeated = true;
                while (repeated) {
                    idx[j] = rng.integer(0, static_cast<int>(pts.size()) - 1);
                    repeated = std::find(idx, idx + j, idx[j]) != idx + j;
                }
                tuples.push_back(pts[static_cast<std::size_t>(idx[j])].data());
            }
        }
        const double* const* t = tuples.data();
        PredicateCounters k;
        long sum = 0;
        const auto t0 = Clock::now();
        for (int n = 0; n < kCalls; ++n, t += 5) sum += cbr::geom::orient3d(t[0], t[1], t[2], t[3], &k);
        const auto t1 = Clock::now();
        t = tuples.data();
        for (int n = 0; n < kCalls; ++n, t += 5)
            sum += cbr::geom::insphere_sos(t[0], t[1], t[2], t[3], t[4], &k);
        const auto t2 = Clock::now();
        std::printf("%-24s orient3d %5.1f ns/call, filter decides %8.4f%% | insphere_sos %6.1f "
                    "ns/call, filter decides %8.4f%%, perturbed %.4f%%  [%ld]\n",
                    name, ns_per_call(t0, t1, kCalls),
                    100.0 - 100.0 * double(k.orient3d_exact) / kCalls, ns_per_call(t1, t2, kCalls),
                    100.0 - 100.0 * double(k.insphere_exact) / kCalls,
                    100.0 * double(k.insphere_perturbed) / kCalls, sum);
    };
    Rng rng(17);
    std::vector<Point> random_pts;
    for (int i = 0; i < 4096; ++i) random_pts.push_back(rng.point(0, 1));
    run("random in unit cube", random_pts);
    run("grid 16^3, spacing 1", grid(16, 1.0, 0.0));
    run("grid 16^3, spacing 0.1", grid(16, 0.1, -0.8));

    // The exact stage alone, on full-mantissa points (differences exact or
    // not) and on cospherical integer points.
    auto exact_ns = [&](const char* name, const std::vector<Point>& pts) {
        constexpr int kExact = 20000;
        Rng r(18);
        std::vector<const double*> tuples;
        for (int i = 0; i < 5 * kExact; ++i) tuples.push_back(r.pick(pts).data());
        const double* const* t = tuples.data();
        long sum = 0;
        const auto t0 = Clock::now();
        for (int n = 0; n < kExact; ++n, t += 5)
            sum += cbr::geom::detail::orient3d_exact(t[0], t[1], t[2], t[3], nullptr);
        const auto t1 = Clock::now();
        t = tuples.data();
        for (int n = 0; n < kExact; ++n, t += 5)
            sum += cbr::geom::detail::insphere_exact(t[0], t[1], t[2], t[3], t[4], nullptr);
        const auto t2 = Clock::now();
        std::printf("exact stage, %-22s orient3d %6.0f ns, insphere %6.0f ns  [%ld]\n", name,
                    ns_per_call(t0, t1, kExact), ns_per_call(t1, t2, kExact), sum);
    };
    std::vector<Point> near_one, symmetric;
    for (int i = 0; i < 4096; ++i) {
        near_one.push_back(rng.point(1.5, 2.8));   // in [1.06, 1.98): exact differences
        symmetric.push_back(rng.point(-1.4, 1.4));  // mixed signs: mostly inexact ones
    }
    exact_ns("points in [1, 2)", near_one);
    exact_ns("points in [-1, 1]", symmetric);
    exact_ns("integer sphere r^2=50", integer_sphere(50));
}

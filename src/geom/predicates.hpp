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
// the exact stage overflows or underflows, so every answer is exact.
//
// No global mutable state: the optional counters belong to the caller.
#pragma once

#include <cstdint>

namespace cbr::geom {

// Coordinates of the supported range (see above).
inline constexpr double kMinMagnitude = 1e-40;
inline constexpr double kMaxMagnitude = 1e+40;

// How often each stage was reached; owned by the caller (one per mesh), so
// threads never share it. Pass nullptr when not counting.
struct PredicateCounters {
    std::uint64_t orient3d_exact = 0;   // filter failed, exact stage ran
    std::uint64_t insphere_exact = 0;
    std::uint64_t insphere_perturbed = 0;  // exact value was 0, SoS decided
};

// Sign of det[b-a, c-a, d-a]: +1 when (a, b, c, d) is positively oriented
// (d on the side of plane abc that (b-a) x (c-a) points to), -1 when
// negatively oriented, 0 when the four points are coplanar.
int orient3d(const double* a, const double* b, const double* c, const double* d,
             PredicateCounters* counters = nullptr);

// For a positively oriented tetrahedron (a, b, c, d): +1 when e lies strictly
// inside its circumsphere, -1 strictly outside, 0 on it. For a negatively
// oriented one the sign is reversed (it is the sign of one polynomial).
int insphere(const double* a, const double* b, const double* c, const double* d,
             const double* e, PredicateCounters* counters = nullptr);

// insphere with symbolic perturbation (simulation of simplicity): each point
// p is lifted to |p|^2 + eps^k(p) with k given by the lexicographic (x, y, z)
// rank of p among all points (a function of the coordinates only, so the
// answer never depends on ids or argument order beyond the determinant's
// sign rule). Never 0 when orient3d(a, b, c, d) != 0 and the five points are
// pairwise distinct. Equal to insphere() whenever that is non-zero.
int insphere_sos(const double* a, const double* b, const double* c, const double* d,
                 const double* e, PredicateCounters* counters = nullptr);

// For coplanar a, b, c, p with a, b, c not collinear and p distinct from
// them: the conflict test of p against the ghost tetrahedron (a, b, c, oo)
// whose infinite apex lies on the positive side of abc. Defined as
// insphere_sos(a, b, c, q, p) for any q with orient3d(a, b, c, q) > 0 (the
// answer does not depend on q): +1 when p is inside the circumcircle of abc
// (perturbed), -1 outside. Never 0.
int incircle_coplanar_sos(const double* a, const double* b, const double* c, const double* p,
                          PredicateCounters* counters = nullptr);

// True when a, b, c lie on one line (exact).
bool collinear(const double* a, const double* b, const double* c);

// Lexicographic (x, y, z) order of two points; the order the perturbation
// uses. -1, 0 (identical coordinates), +1.
int lexicographic_compare(const double* p, const double* q);

}  // namespace cbr::geom

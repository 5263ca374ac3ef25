// Edge removal's choice of ring triangulation (Shewchuk's dynamic program)
// and the quality measure it maximizes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geom/plane_side.hpp"
#include "geom/predicates.hpp"
#include "mesh/flips.hpp"

namespace cbr::mesh {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Scores of the tetrahedra a triangulation of the shell's ring would make.
class RingScorer {
public:
    // `finite`: storage for the shell's finite vertices (reused).
    RingScorer(const TetMesh& m, VertexId u, VertexId v, const Shell& s, std::vector<VertexId>& finite,
               const RingObjective& objective)
        : m_(m), u_(u), v_(v), ring_(s.ring), finite_(finite), measure_(objective.measure) {
        finite_.clear();
        for (VertexId x : ring_)
            if (x != kGhostVertex) finite_.push_back(x);
        for (VertexId x : {u, v})
            if (x != kGhostVertex) finite_.push_back(x);
    }

    // Ring triangle (i, k, j) in ring order: the worse of (ri, rk, rj, v)
    // and (ri, rj, rk, u); or only the first when that is <= `floor` (the
    // caller then has no use for the triangle: it cannot beat its best).
    double triangle(int i, int k, int j, double floor) const {
        const VertexId a = ring_[static_cast<std::size_t>(i)], b = ring_[static_cast<std::size_t>(k)],
                       c = ring_[static_cast<std::size_t>(j)];
        const double first = tet(a, b, c, v_);
        return first <= floor ? first : std::min(first, tet(a, c, b, u_));
    }

    // Whether ring triangle (i, k, j) cones two valid tetrahedra: the sign
    // test of triangle() without the quality.
    bool valid(int i, int k, int j) const {
        const VertexId a = ring_[static_cast<std::size_t>(i)], b = ring_[static_cast<std::size_t>(k)],
                       c = ring_[static_cast<std::size_t>(j)];
        return positive(a, b, c, v_) && positive(a, c, b, u_);
    }

private:
    bool positive(VertexId a, VertexId b, VertexId c, VertexId d) const {
        const VertexId t[4] = {a, b, c, d};
        for (int g = 0; g < 4; ++g)
            if (t[g] == kGhostVertex) return ghost(t, g) > 0;
        return geom::orient3d(m_.point(a), m_.point(b), m_.point(c), m_.point(d)) > 0;
    }

    double tet(VertexId a, VertexId b, VertexId c, VertexId d) const {
        const VertexId t[4] = {a, b, c, d};
        for (int g = 0; g < 4; ++g)
            if (t[g] == kGhostVertex) return ghost(t, g);
        return measure_(m_.point(a), m_.point(b), m_.point(c), m_.point(d));
    }

    // A ghost is neutral (+inf) when its hull face has every finite vertex
    // of the shell on its inner side (or on it): the rule replace_tets
    // applies to the region's vertices; -inf otherwise.
    double ghost(const VertexId t[4], int g) const {
        // Hull face (p, q, r) with the ghost at position 3, by the even
        // permutation that replace_tets uses.
        VertexId f[4] = {t[0], t[1], t[2], t[3]};
        if (g != 3) {
            std::swap(f[g], f[3]);
            std::swap(f[(g + 1) % 3], f[(g + 2) % 3]);
        }
        geom::PlaneSide side(m_.point(f[0]), m_.point(f[1]), m_.point(f[2]));  // orient3d, plane set up once
        for (VertexId x : finite_) {
            // A vertex of the face is on it (orient3d would need its exact
            // stage to say so: the filter cannot decide a degenerate case).
            if (x == f[0] || x == f[1] || x == f[2]) continue;
            if (side(m_.point(x)) > 0) return -kInf;
        }
        return kInf;
    }

    const TetMesh& m_;
    VertexId u_, v_;
    const std::vector<VertexId>& ring_;
    std::vector<VertexId>& finite_;
    double (*measure_)(const double*, const double*, const double*, const double*);
};

// best(i, j): the best worst-quality over triangulations of the sub-polygon
// r_i .. r_j closed by the chord (i, j); split(i, j): its apex k.
struct RingDp {
    std::size_t n = 0;
    std::vector<double> best;
    std::vector<int> split;
    std::vector<char> possible;               // triangulable(): (i, j) has a valid triangulation
    std::vector<int> first;                   // triangulable(): where possible, the first apex that works
    std::vector<VertexId> finite;             // RingScorer's storage
    std::vector<std::pair<int, int>> todo;    // each_triangle()'s storage
    // Reuses the tables' storage (the caller keeps one RingDp per thread).
    void reset(std::size_t size) {
        n = size;
        best.assign(size * size, kInf);
        split.assign(size * size, -1);
    }
    double& at(int i, int j) { return best[cell(i, j)]; }
    int& apex(int i, int j) { return split[cell(i, j)]; }
    char& feasible(int i, int j) { return possible[cell(i, j)]; }
    int& first_apex(int i, int j) { return first[cell(i, j)]; }
    std::size_t cell(int i, int j) const { return static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j); }
};

// The calling thread's tables, kept from one search to the next. Not
// inlined: a thread_local in a shared library costs a __tls_get_addr call
// per use, and inlined into the search its uses were 2% of a recovery.
[[gnu::noinline]] RingDp& thread_ring_dp() {
    thread_local RingDp dp;
    return dp;
}

// Whether the ring has a triangulation of valid tetrahedra at all: solve()'s
// recurrence on booleans, which stops at the first apex that works and
// never computes a quality. Most rings that flip recovery's nested
// searches try have none (that is why they nest), and for those this is
// all the work; solve() then ranks the rings that have one, and its tables
// are filled only for those. Measured (interleaved runs, medians of user
// seconds, this against the commit before): recovery 0.93-0.96x on the
// upsampled box, golf ball, octocat and feeder body, 0.98x on the guide
// arm. (An earlier sign-only test in front of best_ring_triangulation was
// reverted in 6910161 as within the noise, measured by three single runs.)
bool triangulable(RingDp& dp, const RingScorer& score) {
    const int n = static_cast<int>(dp.n);
    dp.possible.assign(dp.n * dp.n, 0);
    dp.first.resize(dp.n * dp.n);  // read only where feasible
    for (int i = 0; i + 1 < n; ++i) dp.feasible(i, i + 1) = 1;
    for (int len = 2; len < n; ++len)
        for (int i = 0; i + len < n; ++i) {
            const int j = i + len;
            for (int k = i + 1; k < j; ++k)
                if (dp.feasible(i, k) && dp.feasible(k, j) && score.valid(i, k, j)) {
                    dp.feasible(i, j) = 1;
                    dp.first_apex(i, j) = k;
                    break;
                }
        }
    return dp.feasible(0, n - 1);
}

// The triangles of the triangulation whose sub-polygon (i, j) has apex
// apexes[i n + j] (solve()'s split, or triangulable()'s first), from the
// root down, as visit(i, k, j) until it returns false (then false).
template <typename Visit>
bool each_triangle(RingDp& dp, const std::vector<int>& apexes, Visit visit) {
    std::vector<std::pair<int, int>>& todo = dp.todo;
    todo.assign(1, {0, static_cast<int>(dp.n) - 1});
    while (!todo.empty()) {
        const auto [i, j] = todo.back();
        todo.pop_back();
        if (j - i < 2) continue;
        const int k = apexes[dp.cell(i, j)];
        if (!visit(i, k, j)) return false;
        todo.push_back({i, k});
        todo.push_back({k, j});
    }
    return true;
}

// After triangulable(): whether the ring has exactly one valid
// triangulation, the one of the first apexes. It has another exactly when
// some sub-polygon of that one, (i, j) with first apex k, has a later apex
// with valid triangulations on both sides (an earlier one would have been
// first). Then there is nothing to rank: solve() would take it whatever
// the measure, if the measure is above -infinity on every valid
// tetrahedron (RingObjective). Most rings that flip recovery removes are
// so (feeder body: of the rings with a valid triangulation, all of 143,000
// of 3 vertices, 385,000 of 409,000 of 4, 58,000 of 71,000 of 5).
bool only_triangulation(RingDp& dp, const RingScorer& score) {
    return each_triangle(dp, dp.first, [&](int i, int apex, int j) {
        for (int k = apex + 1; k < j; ++k)
            if (dp.feasible(i, k) && dp.feasible(k, j) && score.valid(i, k, j)) return false;
        return true;
    });
}

// With a floor, a sub-polygon whose best is not above it counts as -inf:
// every polygon that contains it then skips that apex without a score.
// Each chord (i, j) closes exactly one sub-polygon, so a chord refused by
// `chord_allowed` drops exactly the triangulations that use it (the root's
// closing edge (0, n - 1) is a side of the ring, never asked about).
void solve(RingDp& dp, const RingScorer& score, const RingObjective& objective, const Shell& shell) {
    const int n = static_cast<int>(dp.n);
    const double floor = objective.floor;
    const bool chords_checked = static_cast<bool>(objective.chord_allowed);
    for (int len = 2; len < n; ++len) {
        for (int i = 0; i + len < n; ++i) {
            const int j = i + len;
            double best = floor;
            for (int k = i + 1; k < j; ++k) {
                double q = std::min(dp.at(i, k), dp.at(k, j));
                if (q <= best) continue;  // cannot beat the best so far
                q = std::min(q, score.triangle(i, k, j, best));
                if (q > best) {
                    best = q;
                    dp.apex(i, j) = k;
                }
            }
            // Asked only of a sub-polygon that has a triangulation above the
            // floor (with a floor, most have none).
            if (chords_checked && len < n - 1 && dp.apex(i, j) >= 0 &&
                !objective.chord_allowed(shell.ring[static_cast<std::size_t>(i)], shell.ring[static_cast<std::size_t>(j)]))
                dp.apex(i, j) = -1;
            dp.at(i, j) = dp.apex(i, j) < 0 ? -kInf : best;
        }
    }
}

void extract(RingDp& dp, const std::vector<int>& apexes, std::vector<RingTriangle>& triangles) {
    triangles.clear();
    each_triangle(dp, apexes, [&triangles](int i, int k, int j) {
        triangles.push_back({i, k, j});
        return true;
    });
}

}  // namespace

double tet_quality(const double* a, const double* b, const double* c, const double* d) {
    if (geom::orient3d(a, b, c, d) <= 0) return -kInf;
    double e[3][3];  // b - a, c - a, d - a
    for (int k = 0; k < 3; ++k) {
        e[0][k] = b[k] - a[k];
        e[1][k] = c[k] - a[k];
        e[2][k] = d[k] - a[k];
    }
    const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                       e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                       e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    double sum = 0;  // squared lengths of the six edges
    for (int k = 0; k < 3; ++k) {
        const double bc = c[k] - b[k], bd = d[k] - b[k], cd = d[k] - c[k];
        sum += e[0][k] * e[0][k] + e[1][k] * e[1][k] + e[2][k] * e[2][k] + bc * bc + bd * bd + cd * cd;
    }
    // 6 V = det; the regular tetrahedron scores 1. The sign is the exact
    // one: a positive tetrahedron whose rounded det is not positive still
    // ranks above every invalid one.
    const double q = 12.0 * std::sqrt(3.0) * det / (sum * std::sqrt(sum));
    return q > 0 ? q : std::numeric_limits<double>::min();
}

bool best_ring_triangulation(const TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                             std::vector<RingTriangle>& triangles, double* min_quality) {
    static const RingObjective shape;  // tet_quality, no floor, every chord
    return best_ring_triangulation(m, u, v, shell, triangles, min_quality, shape);
}

bool best_ring_triangulation(const TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                             std::vector<RingTriangle>& triangles, double* min_quality,
                             const RingObjective& objective) {
    triangles.clear();
    if (min_quality) *min_quality = -kInf;
    if (shell.size() < 3) return false;
    RingDp& dp = thread_ring_dp();
    dp.n = shell.size();
    const RingScorer score(m, u, v, shell, dp.finite, objective);
    // Without a floor, the sign-only test first (most rings of recovery's
    // nested searches have no valid triangulation at all); with one, the
    // floor drops invalid rings as fast, and the test would repeat the
    // signs of every valid one.
    if (objective.floor == -kInf && !triangulable(dp, score)) return false;
    // One valid triangulation: taken without its measure, unless the
    // caller asks for that or may refuse some of its chords.
    if (objective.floor == -kInf && !min_quality && !objective.chord_allowed && only_triangulation(dp, score)) {
        extract(dp, dp.first, triangles);
        return true;
    }
    dp.reset(shell.size());
    solve(dp, score, objective, shell);
    const double best = dp.at(0, static_cast<int>(shell.size()) - 1);
    if (min_quality) *min_quality = best;
    if (best == -kInf) return false;
    extract(dp, dp.split, triangles);
    return true;
}

std::size_t ring_positions_blocking_first(const TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                                          std::vector<std::size_t>& order) {
    const std::size_t n = shell.size();
    order.resize(n);
    if (n < 3) {  // no ear to judge
        std::iota(order.begin(), order.end(), std::size_t{0});
        return 0;
    }
    static const RingObjective signs_only;
    const RingScorer score(m, u, v, shell, thread_ring_dp().finite, signs_only);
    // The blocking positions from the front, the others from the back
    // (reversed, then turned back into ring order).
    std::size_t front = 0, back = n;
    for (std::size_t i = 0; i < n; ++i) {
        const int before = static_cast<int>((i + n - 1) % n), after = static_cast<int>((i + 1) % n);
        if (score.valid(before, static_cast<int>(i), after)) order[--back] = i;
        else order[front++] = i;
    }
    std::reverse(order.begin() + static_cast<std::ptrdiff_t>(back), order.end());
    return front;
}

bool ring_may_be_triangulated(const std::vector<std::size_t>& order, std::size_t blocking) {
    const std::size_t n = order.size(), valid = n - blocking;
    if (n < 4 || valid >= 3) return true;  // of three positions on a cycle of 4 or more, two are not neighbours
    if (valid < 2) return false;
    const std::size_t p = order[blocking], q = order[blocking + 1];  // p < q
    return q - p >= 2 && !(p == 0 && q == n - 1);
}

std::vector<RingTriangle> best_ring_triangulation(const TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                                                  double* min_quality) {
    std::vector<RingTriangle> triangles;
    best_ring_triangulation(m, u, v, shell, triangles, min_quality);
    return triangles;
}

}  // namespace cbr::mesh

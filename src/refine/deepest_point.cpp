#include "refine/deepest_point.hpp"

#include <cmath>
#include <cstddef>

#include "geom/vec3.hpp"

namespace cbr::refine {
namespace {

// Pivots tried before the program is given up (Bland's rule cannot cycle;
// this only bounds the work on a degenerate input).
constexpr int kMaxPivots = 500;
// Tableau entries at most this are zero.
constexpr double kPivotEpsilon = 1e-12;

// Columns of the tableau: x+ (3), x- (3), t, then one slack per half-space,
// then the right-hand side.
constexpr std::size_t kDepth = 6;
constexpr std::size_t kVariables = 7;

}  // namespace

// With x = p - inside and unit normals u_i, the largest ball around p
// inside every half-space has radius t where u_i . x + s_i >= t, s_i the
// distance of `inside` from plane i. So: maximise t subject to
// -u_i . x + t <= s_i, with x split into nonnegative parts (x = x+ - x-)
// and t >= 0. The origin is feasible (s_i >= 0): the simplex method starts
// there with the slacks as its basis, and Bland's rule (the lowest
// improving column, the lowest basic row among ties) keeps it finite.
bool deepest_point(const std::vector<HalfSpace>& spaces, const Point& inside, Point& deepest) {
    const std::size_t rows = spaces.size();
    const std::size_t cols = kVariables + rows + 1;
    const std::size_t rhs = cols - 1;
    std::vector<double> tableau((rows + 1) * cols, 0.0);  // the last row: the objective's reduced costs
    const auto at = [&](std::size_t r, std::size_t c) -> double& { return tableau[r * cols + c]; };
    std::vector<std::size_t> basis(rows);
    for (std::size_t i = 0; i < rows; ++i) {
        const HalfSpace& h = spaces[i];
        const double length = std::sqrt(geom::dot(h.normal.data(), h.normal.data()));
        if (!(length > 0)) return false;
        double slack = -h.offset;
        for (std::size_t k = 0; k < 3; ++k) {
            const double u = h.normal[k] / length;
            at(i, k) = -u;
            at(i, 3 + k) = u;
            slack += h.normal[k] * inside[k];
        }
        at(i, kDepth) = 1;
        at(i, kVariables + i) = 1;
        at(i, rhs) = std::fmax(slack / length, 0.0);
        basis[i] = kVariables + i;
    }
    at(rows, kDepth) = 1;  // maximise t
    for (int pivot = 0; pivot < kMaxPivots; ++pivot) {
        std::size_t enter = cols;
        for (std::size_t c = 0; c < rhs && enter == cols; ++c)
            if (at(rows, c) > kPivotEpsilon) enter = c;
        if (enter == cols) {  // optimal
            double value[kVariables] = {};
            for (std::size_t i = 0; i < rows; ++i)
                if (basis[i] < kVariables) value[basis[i]] = at(i, rhs);
            for (std::size_t k = 0; k < 3; ++k) deepest[k] = inside[k] + value[k] - value[3 + k];
            return true;
        }
        std::size_t leave = rows;
        double best_ratio = 0;
        for (std::size_t i = 0; i < rows; ++i) {
            if (at(i, enter) <= kPivotEpsilon) continue;
            const double ratio = at(i, rhs) / at(i, enter);
            if (leave == rows || ratio < best_ratio || (ratio == best_ratio && basis[i] < basis[leave])) {
                leave = i;
                best_ratio = ratio;
            }
        }
        if (leave == rows) return false;  // unbounded
        const double p = at(leave, enter);
        for (std::size_t c = 0; c < cols; ++c) at(leave, c) /= p;
        for (std::size_t r = 0; r <= rows; ++r) {
            if (r == leave) continue;
            const double f = at(r, enter);
            if (f == 0) continue;
            for (std::size_t c = 0; c < cols; ++c) at(r, c) -= f * at(leave, c);
        }
        basis[leave] = enter;
    }
    return false;
}

}  // namespace cbr::refine

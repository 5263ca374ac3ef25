#include "recover/polygon_triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbr::recover {
namespace {

// Shape of a triangle in 3D: 4 sqrt(3) area / (sum of squared edges), 1 for
// the equilateral one, 0 for a flat one. Only used to choose.
double triangle_quality(const double* a, const double* b, const double* c) {
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = c[k] - b[k];
    }
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double area2 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double s = u[0] * u[0] + u[1] * u[1] + u[2] * u[2] + v[0] * v[0] + v[1] * v[1] + v[2] * v[2] +
                     w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    return s > 0 ? 2.0 * std::sqrt(3.0) * area2 / s : 0.0;
}

// Open segments pq and rs cross at one point interior to both (2D, exact).
bool segments_cross(geom::Projection pr, const double* p, const double* q, const double* r, const double* s) {
    const int a = geom::orient2d(pr, p, q, r), b = geom::orient2d(pr, p, q, s);
    const int c = geom::orient2d(pr, r, s, p), d = geom::orient2d(pr, r, s, q);
    return a * b < 0 && c * d < 0;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<const double*>& loop, geom::Projection pr,
                                                    int turn) {
    const int n = static_cast<int>(loop.size());
    if (n < 3) return {};
    const auto point_in_closed = [&](int i, int j, int k, int x) {
        return turn * geom::orient2d(pr, loop[i], loop[j], loop[x]) >= 0 &&
               turn * geom::orient2d(pr, loop[j], loop[k], loop[x]) >= 0 &&
               turn * geom::orient2d(pr, loop[k], loop[i], loop[x]) >= 0;
    };
    const auto chord_ok = [&](int i, int j) {
        if ((i + 1) % n == j || (j + 1) % n == i) return true;  // a polygon edge
        for (int e = 0; e < n; ++e) {
            const int f = (e + 1) % n;
            if (e == i || e == j || f == i || f == j) continue;
            if (segments_cross(pr, loop[i], loop[j], loop[e], loop[f])) return false;
        }
        return true;
    };
    const auto valid = [&](int i, int j, int k) {
        if (turn * geom::orient2d(pr, loop[i], loop[j], loop[k]) <= 0) return false;
        for (int x = 0; x < n; ++x)
            if (x != i && x != j && x != k && point_in_closed(i, j, k, x)) return false;
        return chord_ok(i, j) && chord_ok(j, k) && chord_ok(i, k);
    };
    // best[i][j]: the best triangulation of the sub-polygon i, i+1, ..., j
    // closed by chord ij; split[i][j]: its apex.
    constexpr double kNone = -1.0;
    std::vector<std::vector<double>> best(n, std::vector<double>(n, kNone));
    std::vector<std::vector<int>> split(n, std::vector<int>(n, -1));
    for (int i = 0; i + 1 < n; ++i) best[i][i + 1] = std::numeric_limits<double>::infinity();
    for (int len = 2; len < n; ++len)
        for (int i = 0; i + len < n; ++i) {
            const int j = i + len;
            for (int k = i + 1; k < j; ++k) {
                if (best[i][k] < 0 || best[k][j] < 0 || !valid(i, k, j)) continue;
                const double q =
                    std::min({triangle_quality(loop[i], loop[k], loop[j]), best[i][k], best[k][j]});
                if (q > best[i][j]) {
                    best[i][j] = q;
                    split[i][j] = k;
                }
            }
        }
    if (best[0][n - 1] < 0) return {};
    std::vector<std::array<int, 3>> out;
    std::vector<std::pair<int, int>> todo{{0, n - 1}};
    while (!todo.empty()) {
        const auto [i, j] = todo.back();
        todo.pop_back();
        if (j - i < 2) continue;
        const int k = split[i][j];
        out.push_back({i, k, j});
        todo.push_back({i, k});
        todo.push_back({k, j});
    }
    return out;
}

}  // namespace cbr::recover

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

// v, on line pq, lies strictly between p and q (2D: compared along the
// projected coordinate in which p and q differ most; exact comparisons).
bool between(geom::Projection pr, const double* p, const double* q, const double* v) {
    const int a = std::fabs(q[pr.u] - p[pr.u]) >= std::fabs(q[pr.v] - p[pr.v]) ? pr.u : pr.v;
    return (p[a] < v[a] && v[a] < q[a]) || (q[a] < v[a] && v[a] < p[a]);
}

}  // namespace

// The side of line ij each vertex is on is found once (it serves the
// vertex and both edges at it); an edge whose ends are on opposite sides
// then crosses the chord when the chord's ends are on opposite sides of
// the edge.
bool chord_is_clear(const std::vector<const double*>& loop, geom::Projection pr, int i, int j) {
    const int n = static_cast<int>(loop.size());
    const double* p = loop[i];
    const double* q = loop[j];
    int small[kMaxOptimalPolygon];
    std::vector<int> large;
    int* side = small;
    if (n > kMaxOptimalPolygon) {
        large.resize(static_cast<std::size_t>(n));
        side = large.data();
    }
    for (int x = 0; x < n; ++x) side[x] = x == i || x == j ? 0 : geom::orient2d(pr, p, q, loop[x]);
    for (int x = 0; x < n; ++x) {
        if (x == i || x == j) continue;
        const double* v = loop[x];
        if (side[x] == 0 && between(pr, p, q, v)) return false;
        const int y = (x + 1) % n;
        if (y == i || y == j || side[x] * side[y] >= 0) continue;
        if (geom::orient2d(pr, v, loop[y], p) * geom::orient2d(pr, v, loop[y], q) < 0) return false;
    }
    return true;
}

std::vector<std::array<int, 3>> triangulate_polygon_by_ears(const std::vector<const double*>& loop,
                                                            geom::Projection pr, int turn, const FlatTriangle& flat) {
    const int n = static_cast<int>(loop.size());
    if (n < 3) return {};
    std::vector<int> prev(n), next(n);
    for (int i = 0; i < n; ++i) {
        prev[i] = (i + n - 1) % n;
        next[i] = (i + 1) % n;
    }
    // Quality of the ear at c, or a negative value when c is not an ear of
    // the polygon left (whose first vertex is `start`).
    int start = 0;
    const auto ear = [&](int c) {
        const int p = prev[c], q = next[c];
        const double *a = loop[p], *b = loop[c], *d = loop[q];
        if (turn * geom::orient2d(pr, a, b, d) <= 0) return -1.0;
        int sorted[3] = {p, c, q};
        std::sort(sorted, sorted + 3);
        if (flat && flat(sorted[0], sorted[1], sorted[2])) return -1.0;
        int x = start;
        do {
            if (x != p && x != c && x != q && turn * geom::orient2d(pr, a, b, loop[x]) >= 0 &&
                turn * geom::orient2d(pr, b, d, loop[x]) >= 0 && turn * geom::orient2d(pr, d, a, loop[x]) >= 0)
                return -1.0;
            x = next[x];
        } while (x != start);
        return triangle_quality(a, b, d);
    };
    std::vector<double> quality(n);
    for (int i = 0; i < n; ++i) quality[i] = ear(i);
    std::vector<std::array<int, 3>> out;
    const auto best_ear = [&] {  // ties to the first from `start`, so the result is deterministic
        int best = -1;
        int x = start;
        do {
            if (quality[x] >= 0 && (best < 0 || quality[x] > quality[best])) best = x;
            x = next[x];
        } while (x != start);
        return best;
    };
    for (int left = n; left > 3; --left) {
        int best = best_ear();
        if (best < 0) {
            // Only the cut ears' neighbours were looked at again: a corner
            // whose triangle held a cut vertex may have become an ear.
            int x = start;
            do {
                quality[x] = ear(x);
                x = next[x];
            } while (x != start);
            best = best_ear();
            if (best < 0) return {};
        }
        std::array<int, 3> t = {prev[best], best, next[best]};
        std::sort(t.begin(), t.end());
        out.push_back(t);
        const int p = prev[best], q = next[best];
        next[p] = q;
        prev[q] = p;
        if (start == best) start = q;
        // Cutting an ear changes the triangles of its neighbours; the other
        // ears keep theirs and stay ears (a vertex fewer can only help).
        quality[p] = ear(p);
        quality[q] = ear(q);
    }
    std::array<int, 3> t = {prev[start], start, next[start]};
    std::sort(t.begin(), t.end());
    if (turn * geom::orient2d(pr, loop[prev[start]], loop[start], loop[next[start]]) <= 0 ||
        (flat && flat(t[0], t[1], t[2])))
        return {};
    out.push_back(t);
    return out;
}

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<const double*>& loop, geom::Projection pr,
                                                    int turn, const FlatTriangle& flat) {
    const int n = static_cast<int>(loop.size());
    if (n < 3) return {};
    if (n > kMaxOptimalPolygon) return triangulate_polygon_by_ears(loop, pr, turn, flat);
    // A chord ij may be a side of a triangle when it is a polygon edge, or
    // when it crosses no polygon edge and passes through no vertex
    // (memoized: each chord is asked about by many triangles).
    std::vector<signed char> chord(static_cast<std::size_t>(n) * n, -1);
    const auto chord_ok = [&](int i, int j) {
        if ((i + 1) % n == j || (j + 1) % n == i) return true;  // a polygon edge
        signed char& known = chord[static_cast<std::size_t>(i) * n + j];
        if (known < 0) known = chord_is_clear(loop, pr, i, j) ? 1 : 0;
        return known == 1;
    };
    // Corner c of triangle (c, d, e), turning with `turn`: no polygon edge
    // at c points strictly into the triangle's angle at c.
    const auto corner_ok = [&](int c, int d, int e) {
        for (const int x : {(c + 1) % n, (c + n - 1) % n}) {
            if (x == d || x == e) continue;
            if (turn * geom::orient2d(pr, loop[c], loop[d], loop[x]) > 0 &&
                turn * geom::orient2d(pr, loop[e], loop[c], loop[x]) > 0)
                return false;
        }
        return true;
    };
    // A triangle of the right turn whose sides are clear chords holds no
    // polygon vertex unless the boundary reaches one of its corners from
    // inside it (from a vertex inside, the boundary must leave the
    // triangle: across a side, which clear chords exclude, or into a
    // corner along an edge pointing into the triangle): O(1) beyond the
    // chords.
    const auto valid = [&](int i, int j, int k) {
        if (turn * geom::orient2d(pr, loop[i], loop[j], loop[k]) <= 0) return false;
        if (flat && flat(i, j, k)) return false;
        return chord_ok(i, j) && chord_ok(j, k) && chord_ok(i, k) && corner_ok(i, j, k) && corner_ok(j, k, i) &&
               corner_ok(k, i, j);
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

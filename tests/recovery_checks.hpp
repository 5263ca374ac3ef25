// The project's own exact checks of a recovered (or refined) mesh, through
// the C API: every input triangle a face, every tetrahedron positively
// oriented, no added point (Steiner or field point) on an input triangle,
// the bounded regions' volume equal to the enclosed volume, regions that
// differ across every input triangle. Shared by test_recover_surfaces.cpp,
// test_refine_surfaces.cpp and test_hard_cases.cpp; include it after
// <doctest/doctest.h>.
#pragma once

#include <doctest/doctest.h>

#include <cbr/cbr.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geom/point_in_triangle.hpp"
#include "geom/predicates.hpp"

namespace cbr::test {

using Face = std::array<std::int64_t, 3>;
inline Face sorted_face(std::int64_t a, std::int64_t b, std::int64_t c) {
    Face f = {a, b, c};
    std::sort(f.begin(), f.end());
    return f;
}

// The four faces of a tetrahedron (a, b, c, d), as local vertex indices.
inline constexpr int kTetFace[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

inline long double six_volume(const double* a, const double* b, const double* c, const double* d) {
    long double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = static_cast<long double>(b[k]) - a[k];
        v[k] = static_cast<long double>(c[k]) - a[k];
        w[k] = static_cast<long double>(d[k]) - a[k];
    }
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Six times the signed volume the triangles enclose (divergence theorem),
// the cones taken from the first point: from the origin, a surface far
// from it (coordinates near 2^44, sizes near 1) would sum cones of about
// 1e40 that cancel to a few hundred, beyond long double's precision.
inline long double six_signed_volume(const std::vector<double>& xyz, const std::vector<std::int64_t>& tris) {
    long double sum = 0;
    if (xyz.size() < 3) return 0;
    const double* origin = xyz.data();
    for (std::size_t i = 0; i + 2 < tris.size(); i += 3)
        sum += six_volume(origin, &xyz[3 * static_cast<std::size_t>(tris[i])],
                          &xyz[3 * static_cast<std::size_t>(tris[i + 1])], &xyz[3 * static_cast<std::size_t>(tris[i + 2])]);
    return sum;
}

// Every directed edge used exactly once, and its reverse too: a closed,
// consistently oriented manifold surface.
inline bool closed_and_consistent(const std::vector<std::int64_t>& tris) {
    std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
    for (std::size_t i = 0; i + 2 < tris.size(); i += 3)
        for (int k = 0; k < 3; ++k) ++directed[{tris[i + k], tris[i + (k + 1) % 3]}];
    for (const auto& [edge, count] : directed)
        if (count != 1 || directed.count({edge.second, edge.first}) == 0) return false;
    return true;
}

// The enclosed volume when the surface is closed and consistently oriented;
// 0 otherwise.
inline long double enclosed_volume(const std::vector<double>& xyz, const std::vector<std::int64_t>& tris) {
    if (!closed_and_consistent(tris)) return 0;
    const long double six = six_signed_volume(xyz, tris);
    return (six < 0 ? -six : six) / 6;
}

// How many of the points `ids` (coordinates in pts, 3 per id) lie on one
// of the triangles `tris` (exact, closed triangles). Each point is tested
// against the triangles whose bounding boxes share its cell of a grid over
// the triangles' box: a triangle holding the point has the point in its
// box, and the cell index is monotone in each coordinate, so that cell is
// among the triangle's.
inline std::size_t points_on_triangles(const std::vector<double>& pts, const std::vector<std::int64_t>& ids,
                                       const std::vector<std::int64_t>& tris) {
    const auto P = [&](std::int64_t v) { return &pts[3 * static_cast<std::size_t>(v)]; };
    const std::size_t count = tris.size() / 3;
    if (count == 0 || ids.empty()) return 0;
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = P(tris[0])[k];
    for (std::int64_t v : tris)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], P(v)[k]), hi[k] = std::max(hi[k], P(v)[k]);
    // A surface of n triangles is about sqrt(n) triangles across: cells
    // about half a triangle wide.
    const int cells = std::clamp(static_cast<int>(2 * std::sqrt(static_cast<double>(count))), 1, 256);
    const auto cell = [&](double x, int k) {
        const double span = hi[k] - lo[k];
        if (!(span > 0)) return 0;
        return std::clamp(static_cast<int>((x - lo[k]) / span * cells), 0, cells - 1);
    };
    const auto key = [&](int x, int y, int z) {
        return (static_cast<std::size_t>(x) * static_cast<std::size_t>(cells) + static_cast<std::size_t>(y)) *
                   static_cast<std::size_t>(cells) + static_cast<std::size_t>(z);
    };
    std::unordered_map<std::size_t, std::vector<std::size_t>> grid;
    for (std::size_t i = 0; i < count; ++i) {
        int a[3], b[3];
        for (int k = 0; k < 3; ++k) {
            const double x0 = P(tris[3 * i])[k], x1 = P(tris[3 * i + 1])[k], x2 = P(tris[3 * i + 2])[k];
            a[k] = cell(std::min({x0, x1, x2}), k);
            b[k] = cell(std::max({x0, x1, x2}), k);
        }
        for (int x = a[0]; x <= b[0]; ++x)
            for (int y = a[1]; y <= b[1]; ++y)
                for (int z = a[2]; z <= b[2]; ++z) grid[key(x, y, z)].push_back(i);
    }
    std::size_t on = 0;
    for (std::int64_t v : ids) {
        const double* p = P(v);
        if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2]) continue;
        const auto it = grid.find(key(cell(p[0], 0), cell(p[1], 1), cell(p[2], 2)));
        if (it == grid.end()) continue;
        for (std::size_t i : it->second)
            on += cbr::geom::point_in_triangle(p, P(tris[3 * i]), P(tris[3 * i + 1]), P(tris[3 * i + 2]));
    }
    return on;
}

// Proves the recovered mesh in `m` for the input points `xyz` and triangles
// `tris` (0-based). The bounded regions must fill `expected_volume` when it
// is positive (nested or shared-face inputs, where the enclosed volume of
// the triangles is not the domain's), else enclosed_volume(xyz, tris) when
// that is defined. With `regions_apart` (a closed surface), the two sides
// of every triangle must lie in different regions; an open surface's
// triangles may have the same region on both sides. Sets
// CBR_PARAM_KEEP_EXTERIOR.
inline void check_recovered(cbr_mesh* m, const std::vector<double>& xyz, const std::vector<std::int64_t>& tris,
                            double expected_volume = 0, bool regions_apart = true) {
    REQUIRE(cbr_mesh_set_param(m, CBR_PARAM_KEEP_EXTERIOR, 1) == CBR_OK);
    const std::int64_t nt = cbr_mesh_tet_count(m), np = cbr_mesh_point_count(m);
    std::vector<std::int64_t> tets(4 * static_cast<std::size_t>(nt));
    std::vector<std::int32_t> regions(static_cast<std::size_t>(nt));
    std::vector<double> pts(3 * static_cast<std::size_t>(np));
    REQUIRE(cbr_mesh_get_tets(m, tets.data()) == CBR_OK);
    REQUIRE(cbr_mesh_get_tet_regions(m, regions.data()) == CBR_OK);
    REQUIRE(cbr_mesh_get_points(m, pts.data()) == CBR_OK);
    auto P = [&](std::int64_t v) { return &pts[3 * static_cast<std::size_t>(v)]; };

    // Input points unchanged, bit for bit.
    REQUIRE(pts.size() >= xyz.size());
    CHECK(std::equal(xyz.begin(), xyz.end(), pts.begin()));
    // Orientation, faces, regions on both sides of each face.
    std::map<Face, std::vector<std::int32_t>> face_regions;
    long double bounded = 0;
    std::size_t inverted = 0;
    for (std::size_t t = 0; t < static_cast<std::size_t>(nt); ++t) {
        const std::int64_t* v = &tets[4 * t];
        if (cbr::geom::orient3d(P(v[0]), P(v[1]), P(v[2]), P(v[3])) <= 0) ++inverted;
        if (regions[t] > 0) bounded += six_volume(P(v[0]), P(v[1]), P(v[2]), P(v[3]));
        for (const auto& f : kTetFace) face_regions[sorted_face(v[f[0]], v[f[1]], v[f[2]])].push_back(regions[t]);
    }
    CHECK(inverted == 0);
    std::size_t missing = 0, same_region = 0;
    for (std::size_t i = 0; i + 2 < tris.size(); i += 3) {
        const auto it = face_regions.find(sorted_face(tris[i], tris[i + 1], tris[i + 2]));
        if (it == face_regions.end()) {
            ++missing;
            continue;
        }
        if (it->second.size() == 2 && it->second[0] == it->second[1]) ++same_region;
    }
    CHECK(missing == 0);
    if (regions_apart) CHECK(same_region == 0);
    // Every point after the input's (the Steiner points among them, and
    // after cbr_mesh_refine its field points): none on an input triangle
    // (exact).
    const auto n = static_cast<std::int64_t>(xyz.size() / 3);
    std::vector<std::int64_t> steiner(static_cast<std::size_t>(cbr_mesh_steiner_count(m)));
    REQUIRE(cbr_mesh_steiner_points(m, steiner.data()) == CBR_OK);
    CHECK(std::all_of(steiner.begin(), steiner.end(), [&](std::int64_t v) { return n <= v && v < np; }));
    std::vector<std::int64_t> added(static_cast<std::size_t>(np - n));
    std::iota(added.begin(), added.end(), n);
    CHECK(points_on_triangles(pts, added, tris) == 0);
    // Volume of the bounded regions = volume of the domain.
    const long double enclosed = expected_volume > 0 ? expected_volume : enclosed_volume(xyz, tris);
    if (enclosed > 0) CHECK(static_cast<double>(bounded / 6 / enclosed) == doctest::Approx(1.0).epsilon(1e-9));
}

}  // namespace cbr::test

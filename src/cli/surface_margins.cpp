// The closest points and the flattest triangle of a surface (see
// surface_margins.hpp).
#include "cli/surface_margins.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cli/surface_topology.hpp"
#include "geom/vec3.hpp"

namespace cbr::cli {
namespace {

using geom::squared_distance;

const double* at(const std::vector<double>& xyz, std::int64_t id) { return &xyz[3 * static_cast<std::size_t>(id)]; }

}  // namespace

ClosestPoints closest_points(const cbr_mesh* mesh, const std::vector<double>& xyz) {
    ClosestPoints out;
    const std::int64_t nt = cbr_mesh_tet_count(mesh);
    if (nt <= 0 || cbr_mesh_point_count(mesh) != static_cast<std::int64_t>(xyz.size() / 3)) return out;
    std::vector<std::int64_t> tets(4 * static_cast<std::size_t>(nt));
    if (cbr_mesh_get_tets(mesh, tets.data()) != CBR_OK) return out;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < tets.size(); t += 4)
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                std::int64_t a = tets[t + static_cast<std::size_t>(i)], b = tets[t + static_cast<std::size_t>(j)];
                if (a > b) std::swap(a, b);
                const double d2 = squared_distance(at(xyz, a), at(xyz, b));
                // Ties go to the smaller pair of ids: the same answer
                // whatever the order of the tetrahedra.
                if (d2 < best || (d2 == best && (a < out.a || (a == out.a && b < out.b)))) {
                    best = d2;
                    out.a = a;
                    out.b = b;
                }
            }
    out.found = std::isfinite(best);
    out.distance = std::sqrt(best);
    return out;
}

FlattestTriangle flattest_triangle(const std::vector<double>& xyz, const std::vector<std::int64_t>& tris) {
    FlattestTriangle out;
    const auto n = static_cast<std::int64_t>(xyz.size() / 3);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
        const std::int64_t a = tris[t], b = tris[t + 1], c = tris[t + 2];
        if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= n || a == b || b == c || a == c) continue;
        const double* p = at(xyz, a);
        const double* q = at(xyz, b);
        const double* r = at(xyz, c);
        const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        const double v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
        double normal[3];
        geom::cross(u, v, normal);
        const double longest2 = std::max({squared_distance(p, q), squared_distance(q, r), squared_distance(p, r)});
        // Smallest height = 2 area / longest edge = |u x v| / L; over L.
        const double ratio = std::sqrt(geom::dot(normal, normal)) / longest2;
        if (!(ratio < best)) continue;
        best = ratio;
        out.triangle = static_cast<std::int64_t>(t / 3);
    }
    out.found = std::isfinite(best);
    out.height_ratio = best;
    return out;
}

bool SurfaceMargins::nearly_degenerate() const {
    return (closest.found && diagonal > 0 && closest.distance < kNearlyDegenerate * diagonal) ||
           (flattest.found && flattest.height_ratio < kNearlyDegenerate);
}

SurfaceMargins measure_margins(const cbr_mesh* mesh, const std::vector<double>& xyz,
                               const std::vector<std::int64_t>& tris) {
    SurfaceMargins out;
    out.closest = closest_points(mesh, xyz);
    out.flattest = flattest_triangle(xyz, tris);
    const BoundingBox box = bounding_box(xyz);
    if (!box.empty) {
        double sum = 0;
        for (std::size_t k = 0; k < 3; ++k) sum += (box.hi[k] - box.lo[k]) * (box.hi[k] - box.lo[k]);
        out.diagonal = std::sqrt(sum);
    }
    return out;
}

}  // namespace cbr::cli

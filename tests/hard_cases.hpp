// Hard inputs for boundary recovery, built in the tests (issue 3): closed
// triangle surfaces, each closed part oriented outward, 0-based. Planar
// faces made of several triangles use exactly repeated coordinates (small
// integers, dyadic rationals, or one double reused), so that coplanar faces
// are exactly coplanar.
//
//   schonhardt_stack()      three Schonhardt prisms stacked, sharing their
//                           middle triangles (3 regions)
//   slit_cube()             the unit cube with a slot 1e-6 wide cut into
//                           its top face
//   sphere_box()            a box with nine spherical inclusions, both sides
//                           of each sphere meshed (10 regions)
//   two_cubes_sharing_face() the shared square appears once (2 regions)
//   cube_in_cube()          a cube inside a cube (2 regions: the inner cube
//                           and the shell between them)
//   chazelle_polyhedron()   a box with grooves cut from the top (along y)
//                           and from the bottom (along x) whose edges nearly
//                           touch
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "test_util.hpp"

namespace cbr::test {

// Builds a Polyhedron: points merged by their exact coordinates, triangles
// turned so that their normal agrees with a given outward direction.
class SurfaceBuilder {
  public:
    using Vec = std::array<double, 3>;

    std::int64_t point(double x, double y, double z) {
        const Vec key = {x, y, z};
        const auto it = ids_.find(key);
        if (it != ids_.end()) return it->second;
        const auto id = static_cast<std::int64_t>(p_.xyz.size() / 3);
        p_.xyz.insert(p_.xyz.end(), {x, y, z});
        ids_.emplace(key, id);
        return id;
    }
    Vec at(std::int64_t v) const {
        const auto i = 3 * static_cast<std::size_t>(v);
        return {p_.xyz[i], p_.xyz[i + 1], p_.xyz[i + 2]};
    }
    // Triangle abc, reversed if its normal points against `outward`.
    void tri(std::int64_t a, std::int64_t b, std::int64_t c, const Vec& outward) {
        const Vec pa = at(a), pb = at(b), pc = at(c);
        const Vec u = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
        const Vec v = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
        const Vec n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        if (n[0] * outward[0] + n[1] * outward[1] + n[2] * outward[2] < 0) std::swap(b, c);
        p_.tris.insert(p_.tris.end(), {a, b, c});
    }
    // Convex quadrilateral abcd (in cyclic order), split along ac.
    void quad(std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d, const Vec& outward) {
        tri(a, b, c, outward);
        tri(a, c, d, outward);
    }
    // Simple planar polygon (cyclic order, either direction), triangulated
    // without new points by ear clipping in the coordinate plane most
    // nearly parallel to it. An ear is cut only when no other vertex lies in
    // or on it. Meant for small polygons with dyadic coordinates, where the
    // double orientation tests below are exact.
    void polygon(std::vector<std::int64_t> loop, const Vec& outward) {
        int drop = 0;
        for (int k = 1; k < 3; ++k)
            if (std::fabs(outward[k]) > std::fabs(outward[drop])) drop = k;
        const int u = (drop + 1) % 3, w = (drop + 2) % 3;
        auto orient = [&](std::int64_t a, std::int64_t b, std::int64_t c) {
            const Vec pa = at(a), pb = at(b), pc = at(c);
            const double det = (pb[u] - pa[u]) * (pc[w] - pa[w]) - (pb[w] - pa[w]) * (pc[u] - pa[u]);
            return (det > 0) - (det < 0);
        };
        double area = 0;
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const Vec a = at(loop[i]), b = at(loop[(i + 1) % loop.size()]);
            area += a[u] * b[w] - a[w] * b[u];
        }
        if (area < 0) std::reverse(loop.begin(), loop.end());
        while (loop.size() > 3) {
            const std::size_t n = loop.size();
            bool cut = false;
            for (std::size_t i = 0; i < n && !cut; ++i) {
                const std::int64_t a = loop[(i + n - 1) % n], b = loop[i], c = loop[(i + 1) % n];
                if (orient(a, b, c) <= 0) continue;
                bool empty = true;
                for (std::int64_t q : loop)
                    if (q != a && q != b && q != c && orient(a, b, q) >= 0 && orient(b, c, q) >= 0 &&
                        orient(c, a, q) >= 0)
                        empty = false;
                if (!empty) continue;
                tri(a, b, c, outward);
                loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(i));
                cut = true;
            }
            if (!cut) return;  // not simple: leaves a hole, which the surface checks report
        }
        tri(loop[0], loop[1], loop[2], outward);
    }
    // The six faces of the box [lo, hi], two triangles each, outward;
    // `skip` (0..5 = axis * 2 + side) leaves one face out.
    void box(const Vec& lo, const Vec& hi, int skip = -1) {
        for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
                if (axis * 2 + side == skip) continue;
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                std::array<std::int64_t, 4> c{};
                const double cu[4] = {lo[u], hi[u], hi[u], lo[u]}, cv[4] = {lo[v], lo[v], hi[v], hi[v]};
                for (int k = 0; k < 4; ++k) {
                    Vec q{};
                    q[axis] = side ? hi[axis] : lo[axis];
                    q[u] = cu[k];
                    q[v] = cv[k];
                    c[k] = point(q[0], q[1], q[2]);
                }
                Vec n = {0, 0, 0};
                n[axis] = side ? 1 : -1;
                quad(c[0], c[1], c[2], c[3], n);
            }
    }
    // A sphere: the octahedron with each face cut into n*n triangles, its
    // points pushed onto the sphere; outward.
    void sphere(const Vec& centre, double radius, int n) {
        auto grid = [&](int x, int y, int z) {
            const double len = std::sqrt(double(x * x + y * y + z * z));
            return point(centre[0] + radius * x / len, centre[1] + radius * y / len, centre[2] + radius * z / len);
        };
        for (int sx = -1; sx <= 1; sx += 2)
            for (int sy = -1; sy <= 1; sy += 2)
                for (int sz = -1; sz <= 1; sz += 2) {
                    auto g = [&](int i, int j) { return grid(sx * i, sy * j, sz * (n - i - j)); };
                    for (int i = 0; i < n; ++i)
                        for (int j = 0; i + j < n; ++j) {
                            add_outward(g(i, j), g(i + 1, j), g(i, j + 1), centre);
                            if (i + j + 2 <= n) add_outward(g(i + 1, j), g(i + 1, j + 1), g(i, j + 1), centre);
                        }
                }
    }
    Polyhedron take() { return std::move(p_); }

  private:
    // Triangle oriented away from `centre`.
    void add_outward(std::int64_t a, std::int64_t b, std::int64_t c, const Vec& centre) {
        const Vec pa = at(a), pb = at(b), pc = at(c);
        tri(a, b, c, {pa[0] + pb[0] + pc[0] - 3 * centre[0], pa[1] + pb[1] + pc[1] - 3 * centre[1],
                      pa[2] + pb[2] + pc[2] - 3 * centre[2]});
    }
    Polyhedron p_;
    std::map<Vec, std::int64_t> ids_;
};

// Schonhardt-type prisms stacked: `triangle_levels` triangles of radius
// `radius` (z = 0, 1, ...), each turned by `twist` from the one below, the
// lateral quadrilaterals split along the reflex diagonals. The bottom and
// top triangles are faces; with `shared_levels` the ones between are too
// (their edges then have three triangles: one region per prism). Triangle
// order: the bottom, then per prism its six laterals followed by its upper
// triangle when that is a face. Schonhardt's prism: (2, 30 degrees, false).
inline Polyhedron twisted_prisms(int triangle_levels, double twist, bool shared_levels, double radius = 1.0) {
    const double pi = 3.14159265358979323846;
    Polyhedron p;
    for (int level = 0; level < triangle_levels; ++level)
        for (int i = 0; i < 3; ++i) {
            const double a = 2 * pi * i / 3 + level * twist;
            p.xyz.insert(p.xyz.end(), {radius * std::cos(a), radius * std::sin(a), double(level)});
        }
    p.tris = {0, 2, 1};
    for (int level = 0; level + 1 < triangle_levels; ++level) {
        const int b = 3 * level, u = 3 * (level + 1);
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3;
            p.tris.insert(p.tris.end(), {b + i, b + j, u + j, b + i, u + j, u + i});
        }
        if (shared_levels || level + 2 == triangle_levels) p.tris.insert(p.tris.end(), {u, u + 1, u + 2});
    }
    return p;
}

// Three Schonhardt prisms stacked: level L (z = L, 0..3) is the triangle of
// radius 1 turned by L * 30 degrees, each prism joins two levels with the
// twisted diagonals of schonhardt_prism(). The triangles of levels 1 and 2
// are shared faces (they appear once): three regions. 4 + 18 triangles.
inline Polyhedron schonhardt_stack() {
    const double pi = 3.14159265358979323846;
    Polyhedron p;
    for (int level = 0; level < 4; ++level)
        for (int i = 0; i < 3; ++i) {
            const double a = 2 * pi * i / 3 + level * pi / 6;
            p.xyz.insert(p.xyz.end(), {std::cos(a), std::sin(a), double(level)});
        }
    p.tris = {0, 2, 1, 9, 10, 11, 3, 4, 5, 6, 7, 8};  // bottom, top, the two shared levels
    for (int level = 0; level < 3; ++level) {
        const int b = 3 * level, t = b + 3;
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3;
            p.tris.insert(p.tris.end(), {b + i, b + j, t + j, b + i, t + j, t + i});
        }
    }
    return p;
}

// The unit cube with a slot cut into its top face: x in [0.5, 0.5 + width],
// y in [0.25, 0.75], z in [0.5, 1]. The top face is a square with a
// rectangular hole (a frame of four trapezoids). 28 triangles, 16 points.
inline Polyhedron slit_cube(double width = 1e-6) {
    SurfaceBuilder b;
    const double x0 = 0.5, x1 = 0.5 + width, y0 = 0.25, y1 = 0.75, zb = 0.5;
    // Bottom and the four sides of the cube.
    const std::int64_t c000 = b.point(0, 0, 0), c100 = b.point(1, 0, 0), c110 = b.point(1, 1, 0),
                       c010 = b.point(0, 1, 0), c001 = b.point(0, 0, 1), c101 = b.point(1, 0, 1),
                       c111 = b.point(1, 1, 1), c011 = b.point(0, 1, 1);
    b.quad(c000, c100, c110, c010, {0, 0, -1});
    b.quad(c000, c100, c101, c001, {0, -1, 0});
    b.quad(c100, c110, c111, c101, {1, 0, 0});
    b.quad(c110, c010, c011, c111, {0, 1, 0});
    b.quad(c010, c000, c001, c011, {-1, 0, 0});
    // Top frame: outer square corners o[k], slot rim corners r[k].
    const std::int64_t o[4] = {c001, c101, c111, c011};
    const std::int64_t r[4] = {b.point(x0, y0, 1), b.point(x1, y0, 1), b.point(x1, y1, 1), b.point(x0, y1, 1)};
    for (int k = 0; k < 4; ++k) b.quad(o[k], o[(k + 1) % 4], r[(k + 1) % 4], r[k], {0, 0, 1});
    // The slot: its floor and four walls, facing into the slot.
    const std::int64_t f[4] = {b.point(x0, y0, zb), b.point(x1, y0, zb), b.point(x1, y1, zb), b.point(x0, y1, zb)};
    b.quad(f[0], f[1], f[2], f[3], {0, 0, 1});
    b.quad(f[0], f[1], r[1], r[0], {0, 1, 0});
    b.quad(f[1], f[2], r[2], r[1], {-1, 0, 0});
    b.quad(f[2], f[3], r[3], r[2], {0, -1, 0});
    b.quad(f[3], f[0], r[0], r[3], {1, 0, 0});
    return b.take();
}

// The box [0,3] x [0,3] x [0,2] (two triangles a face) holding nine spheres
// of radius 3/8 centred at (i + 1/2, j + 1/2, 1): the sphere triangles appear
// once and separate each inclusion from the box: ten regions. `n`: each
// octant of a sphere is cut into n*n triangles.
inline Polyhedron sphere_box(int n = 4) {
    SurfaceBuilder b;
    b.box({0, 0, 0}, {3, 3, 2});
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) b.sphere({i + 0.5, j + 0.5, 1}, 0.375, n);
    return b.take();
}

// [0,1]^3 and [1,2] x [0,1]^2: the square x = 1 appears once (two
// triangles, facing +x), the other faces outward: two regions.
inline Polyhedron two_cubes_sharing_face() {
    SurfaceBuilder b;
    b.box({0, 0, 0}, {1, 1, 1}, /*skip x = 1*/ 1);
    b.box({1, 0, 0}, {2, 1, 1}, /*skip x = 1*/ 0);
    const std::int64_t a = b.point(1, 0, 0), c = b.point(1, 1, 0), d = b.point(1, 1, 1), e = b.point(1, 0, 1);
    b.quad(a, c, d, e, {1, 0, 0});
    return b.take();
}

// [1,2]^3 inside [0,3]^3, both outward: two regions (the inner cube and
// the shell between the cubes).
inline Polyhedron cube_in_cube() {
    SurfaceBuilder b;
    b.box({0, 0, 0}, {3, 3, 3});
    b.box({1, 1, 1}, {2, 2, 2});
    return b.take();
}

// A Chazelle-style polyhedron: the box [0,5] x [0,5] x [0,2] with `grooves`
// V-shaped grooves cut from the top along y (centred at x = 1, 2, ...,
// half-width 1/4, their bottom edges at z = 1 + gap/2) and as many cut from
// the bottom along x (centred at y = 1, 2, ..., their top edges at
// z = 1 - gap/2): the two families of edges pass within `gap` of each other
// (Chazelle 1984). All coordinates dyadic. The four side faces are notched
// polygons, triangulated by ear clipping.
inline Polyhedron chazelle_polyhedron(int grooves = 4, double gap = 1.0 / 256) {
    SurfaceBuilder b;
    const double W = grooves + 1, H = 2, a = 0.25, zt = 1 + gap / 2, zb = 1 - gap / 2;
    // Top: strips between the grooves, and each groove's two walls.
    for (int k = 0; k <= grooves; ++k) {
        const double xl = k == 0 ? 0 : k + a, xh = k == grooves ? W : k + 1 - a;
        b.quad(b.point(xl, 0, H), b.point(xh, 0, H), b.point(xh, W, H), b.point(xl, W, H), {0, 0, 1});
    }
    for (int k = 1; k <= grooves; ++k) {
        const double c = k;
        b.quad(b.point(c - a, 0, H), b.point(c, 0, zt), b.point(c, W, zt), b.point(c - a, W, H), {H - zt, 0, a});
        b.quad(b.point(c, 0, zt), b.point(c + a, 0, H), b.point(c + a, W, H), b.point(c, W, zt), {zt - H, 0, a});
    }
    // Bottom: the same turned by 90 degrees and upside down.
    for (int k = 0; k <= grooves; ++k) {
        const double yl = k == 0 ? 0 : k + a, yh = k == grooves ? W : k + 1 - a;
        b.quad(b.point(0, yl, 0), b.point(W, yl, 0), b.point(W, yh, 0), b.point(0, yh, 0), {0, 0, -1});
    }
    for (int k = 1; k <= grooves; ++k) {
        const double d = k;
        b.quad(b.point(0, d - a, 0), b.point(W, d - a, 0), b.point(W, d, zb), b.point(0, d, zb), {0, zb, -a});
        b.quad(b.point(0, d, zb), b.point(W, d, zb), b.point(W, d + a, 0), b.point(0, d + a, 0), {0, -zb, -a});
    }
    // Sides y = 0 and y = W: notched at the top; x = 0 and x = W: notched at
    // the bottom.
    for (int side = 0; side < 2; ++side) {
        const double y = side ? W : 0;
        std::vector<std::int64_t> loop = {b.point(0, y, 0), b.point(W, y, 0), b.point(W, y, H)};
        for (int k = grooves; k >= 1; --k)
        {
            loop.push_back(b.point(k + a, y, H));
            loop.push_back(b.point(k, y, zt));
            loop.push_back(b.point(k - a, y, H));
        }
        loop.push_back(b.point(0, y, H));
        b.polygon(loop, {0, side ? 1.0 : -1.0, 0});
    }
    for (int side = 0; side < 2; ++side) {
        const double x = side ? W : 0;
        std::vector<std::int64_t> loop = {b.point(x, 0, H), b.point(x, W, H), b.point(x, W, 0)};
        for (int k = grooves; k >= 1; --k)
        {
            loop.push_back(b.point(x, k + a, 0));
            loop.push_back(b.point(x, k, zb));
            loop.push_back(b.point(x, k - a, 0));
        }
        loop.push_back(b.point(x, 0, 0));
        b.polygon(loop, {side ? 1.0 : -1.0, 0, 0});
    }
    return b.take();
}

// Volume of chazelle_polyhedron(grooves, gap): the box less the grooves'
// triangular prisms.
inline double chazelle_volume(int grooves = 4, double gap = 1.0 / 256) {
    const double W = grooves + 1, H = 2, a = 0.25, zt = 1 + gap / 2, zb = 1 - gap / 2;
    return W * W * H - grooves * W * a * (H - zt) - grooves * W * a * zb;
}

}  // namespace cbr::test

#include "cli/demo_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace cbr::cli {
namespace {

using Tri = std::array<std::int64_t, 3>;

struct Builder {
    DemoSurface& s;
    std::int64_t add_point(double x, double y, double z) {
        s.xyz.insert(s.xyz.end(), {x, y, z});
        return static_cast<std::int64_t>(s.xyz.size() / 3 - 1);
    }
    void add_tri(std::int64_t a, std::int64_t b, std::int64_t c, std::int32_t label) {
        s.tris.insert(s.tris.end(), {a, b, c});
        s.labels.push_back(label);
    }
};

// The six faces of the box, each an n_u x n_v grid split into triangles,
// sharing the points of their common edges; normals point outward.
void add_box(Builder& b, int cells) {
    const double size[3] = {3, 3, 1};
    const int n[3] = {3 * cells, 3 * cells, cells};
    std::map<std::array<int, 3>, std::int64_t> ids;  // grid index -> point id
    auto point = [&](std::array<int, 3> g) {
        auto it = ids.find(g);
        if (it != ids.end()) return it->second;
        const std::int64_t id = b.add_point(size[0] * g[0] / n[0], size[1] * g[1] / n[1], size[2] * g[2] / n[2]);
        ids.emplace(g, id);
        return id;
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            for (int i = 0; i < n[u]; ++i)
                for (int j = 0; j < n[v]; ++j) {
                    std::array<int, 3> g00{}, g10{}, g01{}, g11{};
                    for (auto* g : {&g00, &g10, &g01, &g11}) (*g)[axis] = side * n[axis];
                    g00[u] = i, g00[v] = j;
                    g10[u] = i + 1, g10[v] = j;
                    g01[u] = i, g01[v] = j + 1;
                    g11[u] = i + 1, g11[v] = j + 1;
                    const std::int64_t a = point(g00), bb = point(g10), c = point(g11), d = point(g01);
                    // (u, v, axis) is right-handed: counterclockwise in (u, v)
                    // faces +axis, which is outward on side 1.
                    if (side == 1) {
                        b.add_tri(a, bb, c, 1);
                        b.add_tri(a, c, d, 1);
                    } else {
                        b.add_tri(a, c, bb, 1);
                        b.add_tri(a, d, c, 1);
                    }
                }
        }
    }
}

void add_sphere(Builder& b, const double centre[3], double radius, int levels, std::int32_t label) {
    const double t = (1 + std::sqrt(5.0)) / 2;
    std::vector<std::array<double, 3>> p = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0},
                                            {0, -1, t}, {0, 1, t},  {0, -1, -t}, {0, 1, -t},
                                            {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    std::vector<Tri> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                          {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                          {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> mid;
        auto midpoint = [&](std::int64_t i, std::int64_t j) {
            const auto key = std::minmax(i, j);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            p.push_back({(p[i][0] + p[j][0]) / 2, (p[i][1] + p[j][1]) / 2, (p[i][2] + p[j][2]) / 2});
            return mid[key] = static_cast<std::int64_t>(p.size() - 1);
        };
        std::vector<Tri> next;
        for (const Tri& tri : f) {
            const std::int64_t ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]), ca = midpoint(tri[2], tri[0]);
            next.insert(next.end(), {Tri{tri[0], ab, ca}, Tri{tri[1], bc, ab}, Tri{tri[2], ca, bc}, Tri{ab, bc, ca}});
        }
        f.swap(next);
    }
    const std::int64_t first = static_cast<std::int64_t>(b.s.xyz.size() / 3);
    for (const auto& q : p) {
        const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        b.add_point(centre[0] + radius * q[0] / len, centre[1] + radius * q[1] / len, centre[2] + radius * q[2] / len);
    }
    for (const Tri& tri : f) b.add_tri(first + tri[0], first + tri[1], first + tri[2], label);
}

}  // namespace

DemoSurface nine_sphere_box(int box_cells, int sphere_levels) {
    DemoSurface s;
    Builder b{s};
    add_box(b, box_cells);
    std::int32_t label = 2;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double centre[3] = {0.5 + i, 0.5 + j, 0.5};
            add_sphere(b, centre, 0.3, sphere_levels, label++);
        }
    return s;
}

}  // namespace cbr::cli

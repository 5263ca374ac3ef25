// Test helper of test_cli.sh: reads a Medit .mesh volume mesh with the
// project's own reader (cbr::io::read_medit_volume) and prints its counts:
//
//   cli_mesh_info OUT.mesh [SURFACE]
//   points 2540 tetrahedra 12286 triangles 5040 regions 10 steiner 0
//   unused points 0
//
// (the points no tetrahedron uses, on a line of their own).
// With SURFACE (any format read_surface knows), also checks that the mesh
// starts with the surface's points, bit for bit, and holds its triangles
// and labels unchanged: prints "surface identical", or the first
// difference and exits 1. Exit 2 when a file cannot be read.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <set>
#include <vector>

#include "io/read_surface.hpp"

namespace {

int compare(const cbr::io::VolumeMesh& m, const cbr::io::SurfaceMesh& s) {
    if (m.num_points() < s.num_points()) {
        std::printf("surface DIFFERENT: %zu points in the mesh, %zu in the surface\n", m.num_points(), s.num_points());
        return 1;
    }
    for (std::size_t i = 0; i < s.xyz.size(); ++i) {
        if (std::memcmp(&m.xyz[i], &s.xyz[i], sizeof(double)) != 0) {
            std::printf("surface DIFFERENT: point %zu, coordinate %zu: %.17g vs %.17g\n", i / 3, i % 3, m.xyz[i],
                        s.xyz[i]);
            return 1;
        }
    }
    if (m.tris != s.tris) {
        std::printf("surface DIFFERENT: the triangles differ\n");
        return 1;
    }
    for (std::size_t t = 0; t < s.labels.size(); ++t) {
        if (m.tri_labels[t] != s.labels[t]) {
            std::printf("surface DIFFERENT: triangle %zu has label %d, not %d\n", t, m.tri_labels[t], s.labels[t]);
            return 1;
        }
    }
    std::printf("surface identical\n");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: cli_mesh_info OUT.mesh [SURFACE]\n");
        return 2;
    }
    cbr::io::VolumeMesh m;
    if (const cbr::io::Status st = cbr::io::read_medit_volume(argv[1], m); !st) {
        std::fprintf(stderr, "cli_mesh_info: %s\n", st.message.c_str());
        return 2;
    }
    std::size_t steiner = 0;
    for (const auto flag : m.is_steiner) steiner += flag != 0 ? 1 : 0;
    const std::set<std::int32_t> regions(m.tet_regions.begin(), m.tet_regions.end());
    std::printf("points %zu tetrahedra %zu triangles %zu regions %zu steiner %zu\n", m.num_points(), m.num_tets(),
                m.num_triangles(), regions.size(), steiner);
    std::vector<char> used(m.num_points(), 0);
    for (const std::int64_t id : m.tets)
        if (id >= 0 && static_cast<std::size_t>(id) < used.size()) used[static_cast<std::size_t>(id)] = 1;
    std::printf("unused points %zu\n", static_cast<std::size_t>(std::count(used.begin(), used.end(), 0)));
    if (argc == 2) return 0;
    cbr::io::SurfaceMesh s;
    if (const cbr::io::Status st = cbr::io::read_surface(argv[2], s); !st) {
        std::fprintf(stderr, "cli_mesh_info: %s\n", st.message.c_str());
        return 2;
    }
    return compare(m, s);
}
